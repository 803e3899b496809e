// Baseline row: the kernel's arithmetic (BASELINE_KERNEL_ARITHMETIC, baseline_impl.h), strict,
// double (flags in benchmarks/CMakeLists.txt): the shared headers' operations per sample,
// vectorised by g++, to separate the compiler's share of the kernel's speed from the arithmetic's.

#define BASELINE_KERNEL_ARITHMETIC 1
#define BASELINE_NS bb_kernel_arith_double
#define BASELINE_FN replicas_kernel_arith_double
#include "baseline_impl.h"

static_assert(sizeof(bb_kernel_arith_double::bb_real) == sizeof(double), "baseline_impl.h ignores BB_HOST_REAL_FLOAT");
