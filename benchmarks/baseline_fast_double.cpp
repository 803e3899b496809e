// Baseline flavour: fast, double (flags in benchmarks/CMakeLists.txt).
#define BASELINE_NS bb_fast_double
#define BASELINE_FN replicas_fast_double
#include "baseline_impl.h"
