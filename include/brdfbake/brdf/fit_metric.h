/* The compression g of `brdfbake fit`'s metrics (BB_FIT_METRIC_* of kernel_abi.h), shared by the
 * objective's kernel (kernels/fit.cl) and the host's targets (host/fit/model_fit.cpp), so that
 * both compress alike:
 *   cbrt: g(v) = v^(1/3), the compression of Ngan, Durand and Matusik 2005 ("Experimental
 *         Analysis of BRDF Models", EGSR, sec. 4), applied to v = f cos theta_i;
 *   log:  g(v) = log(1 + v);
 *   l2:   g(v) = v. */
#ifndef BRDFBAKE_BRDF_FIT_METRIC_H
#define BRDFBAKE_BRDF_FIT_METRIC_H

#include "brdfbake/brdf/kernel_abi.h"
#include "brdfbake/brdf/params.h"

#ifdef __OPENCL_C_VERSION__
#define bb_fit_cbrt cbrt
#define bb_fit_log1p log1p
#else
#include <cmath>
#define bb_fit_cbrt std::cbrt
#define bb_fit_log1p std::log1p
#endif

BB_FN bb_real bb_fit_compress(int metric, bb_real v) {
    if (metric == BB_FIT_METRIC_CBRT)
        return bb_fit_cbrt(v);
    if (metric == BB_FIT_METRIC_LOG)
        return bb_fit_log1p(v);
    return v;
}

#endif /* BRDFBAKE_BRDF_FIT_METRIC_H */
