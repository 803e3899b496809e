#!/usr/bin/python3
"""brdfbake's GGX LTC table against the published fit at every common texel (issue 33 item 4).

The measure is the L1 distance between the normalised lobe p = f cos theta_i / E and the LTC
distribution D, integral over the upper hemisphere of |p - D|, computed by the independent numpy
reference (tests/ltc_reference.py, l1_distance_converged_batch: balance-heuristic midpoint rules
on the GGX visible-normal map and the LTC's own map, error |L(n) - L(2n)| plus E's share), for
both matrices at the same texel with the same points; never the fitter's own `distance` channel.

  ltc_compare_published.py BRDFBAKE.csv PUBLISHED [--n N] [--rows T1,T2,..] [--cols A1,A2,..] [--every K]

BRDFBAKE.csv: `brdfbake lut ltc --preset three -o three.csv` (three.js's grid: M from ltc_1 as the
shader unpacks it) or `brdfbake lut ltc --model ggx ... -o FILE.csv` on the published grid; a
`.npy` table (with its `.npy.json`) is read as well.
PUBLISHED: the user's own copy of ltc_code's fit/results/ltc.inc (tabM, linear theta) or of
three.js's examples/jsm/lights/RectAreaLightTexturesLib.js as downloaded (LTC_MAT_1, the later
sqrt(1 - cos theta) fit), or a hand subset (`t a R G B A` lines under a comment naming LTC_MAT_1;
`t a M00 M20 M11 M02 M22` otherwise), read by benchmarks/ltc_compare.py. This project ships none
of that data.

Only texels that are nodes of both grids are compared (no interpolation); a = 0 is left out:
alpha 0 is fitted at brdfbake's floor (1e-4) and at 1e-5 (three.js) or 1e-4 (ltc.inc), so the
two matrices answer different lobes there.

Prints per texel: t a mu alpha d_ours err d_pub err (d_ours - d_pub) / noise, with
noise = err_ours + err_pub (each |L(n) - L(2n)|, an over-estimate of L(2n)'s error for the
second-order rule); then the texels where ours is worse by more than 3 noise, the medians and
where the worse ones lie (by row and by alpha band). Time: CPU seconds of this process.
"""
import argparse
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))
sys.path.insert(0, HERE)
import ltc_reference as ref  # noqa: E402
import ltc_compare as lc  # noqa: E402

ALPHA_BANDS = (0.0, 0.01, 0.05, 0.2, 0.5, 1.01)


def common_texels(brdfbake_csv, published, rows, every, cols=None):
    """[(t, a, mu, alpha, ours M, published M)] at texels that are nodes of both grids, a >= 1."""
    table, size, param = lc.read_published(published)
    out = []
    for row in lc.read_brdfbake_csv(brdfbake_csv):
        t, a = lc.published_index(row["mu"], row["alpha"], size, param)
        pub, kind = lc.published_matrix_at(table, size, t, a)
        t, a = int(round(t)), int(round(a))
        if pub is None or kind != "node" or a == 0 or (rows and t not in rows) or a % every:
            continue
        if cols and a not in cols:
            continue
        ours = ref.matrix_from_channels(row["m00"], row["m02"], row["m11"], row["m20"], row["m22"])
        out.append((t, a, row["mu"], row["alpha"], ours, pub))
    return sorted(out, key=lambda x: (x[0], x[1]))


def where_worse(texels, worse):
    """lines: count of worse texels per row t and per alpha band."""
    lines = []
    by_row = {}
    for (t, a, mu, alpha, _, _), w in zip(texels, worse):
        n, k = by_row.get(t, (0, 0))
        by_row[t] = (n + 1, k + int(w))
    lines.append("worse per row t (of texels in the row): " +
                 ", ".join("t=%d: %d/%d" % (t, k, n) for t, (n, k) in sorted(by_row.items()) if k))
    alphas = np.array([x[3] for x in texels])
    bands = []
    for lo, hi in zip(ALPHA_BANDS[:-1], ALPHA_BANDS[1:]):
        sel = (alphas >= lo) & (alphas < hi)
        bands.append("alpha [%g, %g): %d/%d" % (lo, min(hi, 1.0), int(np.sum(np.array(worse)[sel])), int(sel.sum())))
    lines.append("worse per alpha band: " + ", ".join(bands))
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("brdfbake_csv")
    ap.add_argument("published")
    ap.add_argument("--n", type=int, default=128, help="nodes per axis of the coarser rule (default 128)")
    ap.add_argument("--rows", default=None, help="published rows t to compare (default: all present)")
    ap.add_argument("--cols", default=None, help="published columns a to compare (default: all)")
    ap.add_argument("--every", type=int, default=1, help="every K-th column a")
    ap.add_argument("--sigmas", type=float, default=3.0)
    args = ap.parse_args()
    cpu0, wall0 = time.process_time(), time.time()
    rows = {int(r) for r in args.rows.split(",")} if args.rows else None
    cols = {int(a) for a in args.cols.split(",")} if args.cols else None
    texels = common_texels(args.brdfbake_csv, args.published, rows, args.every, cols)
    if not texels:
        sys.exit("ltc_compare_published: error: no brdfbake texel is a node of the published table "
                 "(for three.js's: brdfbake lut ltc --preset three -o three.csv)")
    mu = np.array([x[2] for x in texels])
    alpha = np.array([x[3] for x in texels])
    mats = np.array([[x[4] for x in texels], [x[5] for x in texels]])
    dist, err, _ = ref.l1_distance_converged_batch(np.maximum(mu, 1e-6), alpha, mats, n=args.n)
    noise = err[0] + err[1]
    z = (dist[0] - dist[1]) / np.maximum(noise, 1e-12)
    worse = z > args.sigmas
    better = z < -args.sigmas
    print("t a mu alpha d_ours err d_pub err diff/noise")
    for i, (t, a, m, al, _, _) in enumerate(texels):
        print("%d %d %.6f %.6f %.5g %.1e %.5g %.1e %+.1f%s" % (t, a, m, al, dist[0, i], err[0, i], dist[1, i], err[1, i],
                                                            z[i], " worse" if worse[i] else ""))
    ratio = dist[0] / np.maximum(dist[1], 1e-12)
    print("# %d texels (rows %s; a = 0 left out)" % (len(texels), ",".join(str(t) for t in sorted({x[0] for x in texels}))))
    print("# worse beyond %g noise: %d; better beyond it: %d; within: %d" % (args.sigmas, worse.sum(), better.sum(),
                                                                         len(texels) - worse.sum() - better.sum()))
    print("# median distance: ours %.5f, published %.5f; median ratio ours/published %.3f (min %.3f, max %.3f)" % (
        np.median(dist[0]), np.median(dist[1]), np.median(ratio), ratio.min(), ratio.max()))
    print("# largest quadrature error: %.1e (median %.1e)" % (err.max(), np.median(err)))
    for line in where_worse(texels, worse):
        print("# " + line)
    if worse.any():
        k = np.argsort(-(dist[0] - dist[1]) * worse)[:10]
        print("# largest excesses: " + "; ".join("t=%d a=%d (alpha %.4f): %.5f vs %.5f" % (
            texels[i][0], texels[i][1], alpha[i], dist[0, i], dist[1, i]) for i in k if worse[i]))
    print("# time: %.1f s CPU, %.1f s wall" % (time.process_time() - cpu0, time.time() - wall0))


if __name__ == "__main__":
    main()
