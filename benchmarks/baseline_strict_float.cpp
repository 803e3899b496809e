// Baseline flavour: strict, float (flags in benchmarks/CMakeLists.txt): real = float
// (BB_HOST_REAL_FLOAT, baseline_impl.h).
#define BB_HOST_REAL_FLOAT 1
#define BASELINE_NS bb_strict_float
#define BASELINE_FN replicas_strict_float
#include "baseline_impl.h"

static_assert(sizeof(bb_strict_float::bb_real) == sizeof(float), "baseline_impl.h ignores BB_HOST_REAL_FLOAT");
