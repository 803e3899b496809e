#!/usr/bin/python3
"""The quad-light study of docs/accuracy.md (issue 33 item 7): what an LTC table is for.

For random parallelogram lights (tests/ltc_reference.py random_quad_light: centre at elevation
15-75 degrees, distance 1-3, sides 0.3-1.5, facing the point), the relative error of
E x (LTC polygon integral) [Heitz, Dupuy, Hill, Neubelt 2016, sec. 3.3 and 4: the corners
transformed by M^-1, clipped to the horizon, Lambert's edge sum] against the true integral of
f cos over the quad (GGX with the height-correlated Smith G2, F = 1; composite Gauss-Legendre on
the quad, kept where it converged to 0.1%), at the same texels and the same lights for

  * brdfbake's table (BRDFBAKE.csv: `brdfbake lut ltc --model ggx ... --format csv`), its M with
    its own magnitude channel (the table as an engine uses it) and with the reference's E (the
    matrix alone);
  * the published fit (PUBLISHED: three.js's LTC_MAT_1, a user's copy or a hand subset of lines
    `t a R G B A` under a comment naming LTC_MAT_1, read by benchmarks/ltc_compare.py; this
    project ships none of its data), its M with the reference's E (its LTC_MAT_2 magnitude is not
    read).

Only brdfbake texels that are published texels (ltc_compare.published_index at integer nodes) with
alpha >= --min-alpha are used (the brute force needs about 4/alpha panels). Prints a Markdown
table per fit: median, 90th percentile and max of |error| / true over lights carrying >= 1% of E,
and of |error| / E over all lights.

  ltc_quad_study.py PUBLISHED BRDFBAKE.csv [--quads K] [--seed S] [--min-alpha A] [--rows T1,T2,..]
                    [--every K]

--rows keeps the published rows t listed (three.js's t = 63 sqrt(1 - cos theta): t = 2, 4 are near
normal incidence, t >= 52 beyond 47 degrees, t = 63 at 90), --every K every K-th column a; with
several rows the table is printed for each row as well as for all.
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


def texel_pairs(published, brdfbake_csv, min_alpha, rows=None, every=1):
    """[(mu, alpha, brdfbake M, brdfbake magnitude, published M, (t, a))] at common texels."""
    table, size, param = lc.read_published(published)
    out = []
    for row in lc.read_brdfbake_csv(brdfbake_csv):
        if row["alpha"] < min_alpha:
            continue
        t, a = lc.published_index(row["mu"], row["alpha"], size, param)
        pub, kind = lc.published_matrix_at(table, size, t, a)
        if pub is None or kind != "node" or (rows and round(t) not in rows) or round(a) % every:
            continue
        m = ref.matrix_from_channels(row["m00"], row["m02"], row["m11"], row["m20"], row["m22"])
        out.append((row["mu"], row["alpha"], m, row["magnitude"], pub, (round(t), round(a))))
    return out


def stats(values):
    v = np.sort(np.array(values))
    if len(v) == 0:
        return "-", "-", "-"
    return "%.4f" % np.median(v), "%.4f" % v[int(0.9 * (len(v) - 1))], "%.4f" % v[-1]


def print_table(title, fits, rel, per_e):
    if title:
        print(title)
    print()
    print("| fit | relative error, median | 90th pct | max | error / E, median | 90th pct | max |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for f in fits:
        print("| %s | %s | %s | %s | %s | %s | %s |" % ((f,) + stats(rel[f]) + stats(per_e[f])))
    print()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("published")
    ap.add_argument("brdfbake_csv")
    ap.add_argument("--quads", type=int, default=4)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--min-alpha", type=float, default=0.02)
    ap.add_argument("--rows", default=None)
    ap.add_argument("--every", type=int, default=1)
    args = ap.parse_args()
    start, cpu0 = time.time(), time.process_time()
    rows = {int(r) for r in args.rows.split(",")} if args.rows else None
    pairs = texel_pairs(args.published, args.brdfbake_csv, args.min_alpha, rows, args.every)
    if not pairs:
        sys.exit("ltc_quad_study: error: no brdfbake texel is a published texel with alpha >= %g" % args.min_alpha)
    fits = ("brdfbake (its magnitude)", "brdfbake (reference E)", "published (reference E)")
    rel = {f: [] for f in fits}
    per_e = {f: [] for f in fits}
    by_row, row_mu = {}, {}
    wins, lights = 0, 0
    rng = np.random.default_rng(args.seed)
    for mu, alpha, m_bb, e_bb, m_pub, (t, a) in pairs:
        e = ref.lobe_terms(mu, alpha, 1024)[0]
        for _ in range(args.quads):
            corner, e1, e2 = ref.random_quad_light(rng)
            true, qerr = ref.quad_fcos_integral(mu, alpha, corner, e1, e2)
            if true <= 0 or qerr > 1e-3 * true:
                continue
            poly = np.array([corner, corner + e1, corner + e1 + e2, corner + e2])
            i_bb, i_pub = ref.ltc_polygon_integral(m_bb, poly), ref.ltc_polygon_integral(m_pub, poly)
            approx = {fits[0]: e_bb * i_bb, fits[1]: e * i_bb, fits[2]: e * i_pub}
            lights += 1
            wins += abs(approx[fits[1]] - true) <= abs(approx[fits[2]] - true)
            row_mu[t] = mu
            row_rel, row_e = by_row.setdefault(t, ({f: [] for f in fits}, {f: [] for f in fits}))
            for f in fits:
                err = abs(approx[f] - true)
                per_e[f].append(err / e)
                row_e[f].append(err / e)
                if true >= 0.01 * e:
                    rel[f].append(err / true)
                    row_rel[f].append(err / true)
        print("texel t %d a %d (mu %.5f alpha %.5f): %d lights so far" % (t, a, mu, alpha, lights), file=sys.stderr,
              flush=True)
    big = len(rel[fits[0]])
    print("%d texels (alpha >= %g), %d lights (%d per texel drawn, seed %d), %d carrying >= 1%% of E" %
          (len(pairs), args.min_alpha, lights, args.quads, args.seed, big))
    print_table("", fits, rel, per_e)
    if len(by_row) > 1:
        for t in sorted(by_row):
            print_table("row t = %d (cos theta = %.5f): %d lights carrying >= 1%% of E" % (
                t, row_mu[t], len(by_row[t][0][fits[0]])), fits, *by_row[t])
    print("brdfbake's matrix (reference E) no worse than the published one at %d of %d lights" % (wins, lights))
    print("time: %.1f s wall, %.1f s CPU" % (time.time() - start, time.process_time() - cpu0))


if __name__ == "__main__":
    main()
