// Plain baseline flavour: -ffast-math, float (flags in benchmarks/CMakeLists.txt): the textbook
// loop of baseline_plain_impl.h with real = float.
#define BB_HOST_REAL_FLOAT 1
#define BASELINE_NS bb_plain_fast_float
#define BASELINE_FN replicas_plain_fast_float
#include "baseline_plain_impl.h"

static_assert(sizeof(bb_plain_fast_float::bb_real) == sizeof(float),
              "baseline_plain_impl.h ignores BB_HOST_REAL_FLOAT");
