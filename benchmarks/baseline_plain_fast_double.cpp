// Plain baseline flavour: -ffast-math, double (flags in benchmarks/CMakeLists.txt): the textbook
// loop of baseline_plain_impl.h with real = double.
#define BASELINE_NS bb_plain_fast_double
#define BASELINE_FN replicas_plain_fast_double
#include "baseline_plain_impl.h"

static_assert(sizeof(bb_plain_fast_double::bb_real) == sizeof(double),
              "baseline_plain_impl.h ignores BB_HOST_REAL_FLOAT");
