// Baseline flavour: strict, double (flags in benchmarks/CMakeLists.txt).
#define BASELINE_NS bb_strict_double
#define BASELINE_FN replicas_strict_double
#include "baseline_impl.h"
