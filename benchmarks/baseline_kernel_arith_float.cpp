// Baseline row: the kernel's arithmetic (BASELINE_KERNEL_ARITHMETIC, baseline_impl.h), strict,
// float (flags in benchmarks/CMakeLists.txt): the shared headers' operations per sample,
// vectorised by g++, to separate the compiler's share of the kernel's speed from the arithmetic's.
#define BB_HOST_REAL_FLOAT 1
#define BASELINE_KERNEL_ARITHMETIC 1
#define BASELINE_NS bb_kernel_arith_float
#define BASELINE_FN replicas_kernel_arith_float
#include "baseline_impl.h"

static_assert(sizeof(bb_kernel_arith_float::bb_real) == sizeof(float), "baseline_impl.h ignores BB_HOST_REAL_FLOAT");
