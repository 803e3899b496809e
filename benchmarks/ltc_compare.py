#!/usr/bin/python3
"""Compare LTC fits by the L1 distance integral of |p - D| over the upper hemisphere (issue 33),
computed independently by tests/ltc_reference.py (numpy, VNDF/LTC multiple-importance midpoint
rule, its own convergence estimate), never by the fitter's own estimate.

  ltc_compare.py PUBLISHED                 the published fit's distance at its texels
  ltc_compare.py PUBLISHED BRDFBAKE.csv    both, per brdfbake texel, and their ratio

PUBLISHED is ltc_code's fit/results/ltc.inc (the `tabM` block), three.js's
examples/jsm/lights/RectAreaLightTexturesLib.js (`LTC_MAT_1`, the later fit), the user's own copy
either way (this project ships none of their data), or a hand subset with lines
`t a M00 M20 M11 M02 M22` (M row-major) or, when a comment names LTC_MAT_1, `t a R G B A`.
Its texel (t, a): alpha = max((a/63)^2, 1e-4), theta = min(1.57, t/63 * 1.57079) (the linear-theta
ltc.inc; x = sqrt(1 - cos theta), theta = min(1.57, acos(1 - x^2)) and alpha floored at 1e-5 for the
later fit three.js ships).
BRDFBAKE.csv is `brdfbake lut ltc --model ggx -o FILE.csv` (GGX with the height-correlated Smith
G2, as ltc_code's brdf_ggx.h), or `brdfbake lut ltc --preset three -o FILE.csv` (three.js's grid and
packing: M from its ltc_1 columns). Where a brdfbake texel's (mu, alpha) is not a published texel, the
published matrix is interpolated linearly in ltc_code's (t, a) index space, as a renderer sampling
the published texture with bilinear filtering would (column `pub_at`: node or interp).

Options: --n N (quadrature nodes per axis, default 256; error = |L(N) - L(2N)|), --every K (every
K-th texel of each published row), --rows T1,T2,... (published rows), --limit K (first K brdfbake
texels), --nodes-only (only brdfbake texels on published texels), --quads K (published mode: K random quad lights per texel with alpha >= 0.02, the
irradiance E x (LTC polygon integral) against the brute-force integral of f cos over the quad; E
is the reference's albedo, so the figure isolates the matrix's error).
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
import ltc_reference as ref  # noqa: E402


def matrix_from_ltc_1(r, g, b, a):
    """M from three.js's LTC_MAT_1 texel (docs/ltc_presets.md): M^-1 / Minv[1][1] with
    Minv[0][0] = R, Minv[2][0] = G, Minv[0][2] = B, Minv[2][2] = A; D ignores M's scale."""
    return np.linalg.inv(ref.matrix_from_channels(r, b, 1.0, g, a))


def read_published(path):
    """({(t, a): M}, size, parametrisation) from ltc_code's ltc.inc (linear theta), three.js's
    RectAreaLightTexturesLib.js (LTC_MAT_1; sqrt(1 - cos theta)), or a hand subset: lines
    `t a M00 M20 M11 M02 M22`, or `t a R G B A` of LTC_MAT_1 when a comment names LTC_MAT_1."""
    text = open(path).read()
    if "tabM" in text:
        size, mats, _ = ref.read_ltc_inc(path)
        return {(t, a): mats[t, a] for t in range(size) for a in range(size)}, size, "theta"
    if "const LTC_MAT_1" in text:
        body = text.split("const LTC_MAT_1")[1].split("[", 1)[1].split("]")[0]
        v = np.array([float(x.replace(" ", "")) for x in body.split(",") if x.strip()]).reshape(64, 64, 4)
        return {(t, a): matrix_from_ltc_1(*v[t, a]) for t in range(64) for a in range(64)}, 64, "sqrt"
    three = "LTC_MAT_1" in text
    table = {}
    for line in text.splitlines():
        if line.strip() and not line.startswith("#"):
            f = line.split()
            t, a, v = int(f[0]), int(f[1]), [float(x) for x in f[2:7]]
            if three:
                table[(t, a)] = matrix_from_ltc_1(*v[:4])
            else:
                m00, m20, m11, m02, m22 = v
                table[(t, a)] = ref.matrix_from_channels(m00, m02, m11, m20, m22)
    return table, 64, "sqrt" if three else "theta"


def _with_mu_alpha_m(row):
    """a brdfbake ltc row completed with mu and alpha (from sqrt_mu, roughness if so named) and,
    for `--preset three`, M from its ltc_1 as three.js's shader reads it."""
    if "mu" not in row and "sqrt_mu" in row:
        row["mu"] = row["sqrt_mu"] ** 2
    if "alpha" not in row and "roughness" in row:
        row["alpha"] = row["roughness"] ** 2
    if "ltc_1.R" in row:
        m = matrix_from_ltc_1(row["ltc_1.R"], row["ltc_1.G"], row["ltc_1.B"], row["ltc_1.A"])
        row.update(m00=m[0, 0], m02=m[0, 2], m11=m[1, 1], m20=m[2, 0], m22=m[2, 2])
    if "magnitude" not in row and "ltc_2.R" in row:
        row["magnitude"] = row["ltc_2.R"]
    return row


def _rows_of_npy(path):
    """rows of a brdfbake `.npy` table: the array [axis 0, axis 1, ..., channel] described by
    PATH.json (axes' `parameter` and `parameter_values`, `channels`)."""
    import json
    desc = json.load(open(path + ".json"))
    data = np.load(path)
    names = [axis["parameter"] for axis in desc["axes"]]
    values = [np.asarray(axis["parameter_values"], float) for axis in desc["axes"]]
    rows = []
    for index in np.ndindex(*data.shape[:-1]):
        row = {name: float(v[i]) for name, v, i in zip(names, values, index)}
        row.update(zip(desc["channels"], (float(x) for x in data[index])))
        rows.append(row)
    return rows


def read_brdfbake_csv(path):
    """rows of a brdfbake ltc table (`.csv`, or `.npy` with its `.npy.json`) as dicts with mu, alpha
    and M's five entries (EXR and .h tables: write the table again with -o FILE.csv or FILE.npy)."""
    if path.endswith(".npy"):
        rows = [_with_mu_alpha_m(r) for r in _rows_of_npy(path)]
        header = list(rows[0]) if rows else []
    elif path.endswith(".csv"):
        header, rows = None, []
        for line in open(path):
            if line.startswith("#") or not line.strip():
                continue
            cells = line.strip().split(",")
            if header is None:
                header = cells
                continue
            rows.append(_with_mu_alpha_m(dict(zip(header, (float(c) for c in cells)))))
    else:
        sys.exit("ltc_compare: error: %s is not a .csv or .npy table (write it with -o FILE.csv)" % path)
    missing = {"mu", "alpha", "m00", "m02", "m11", "m20", "m22"} - set(rows[0] if rows else header or [])
    if missing:
        sys.exit("ltc_compare: error: %s lacks the columns %s" % (path, ", ".join(sorted(missing))))
    return rows


def published_coordinates(t, a, size, parametrisation):
    return (math.cos(ref.ltc_code_view_angle(t, size, parametrisation)),
            ref.ltc_code_alpha(a, size, parametrisation))


def published_index(mu, alpha, size, parametrisation):
    """fractional (t, a) of a (mu, alpha) in ltc_code's axes."""
    theta = math.acos(max(-1.0, min(1.0, mu)))
    if theta >= 1.57 - 1e-7:  # the last row: theta clamped at 1.57 in both parametrisations
        t = size - 1.0
    elif parametrisation == "sqrt":
        t = math.sqrt(max(0.0, 1.0 - mu)) * (size - 1)
    else:
        t = theta / 1.57079 * (size - 1)
    a = math.sqrt(max(alpha, 0.0)) * (size - 1)
    if alpha <= ref.ltc_code_alpha(0, size, parametrisation):  # the first column: alpha floored
        a = 0.0
    return min(max(t, 0.0), size - 1.0), min(max(a, 0.0), size - 1.0)


def published_matrix_at(table, size, t, a):
    """M at fractional (t, a): the node if both are integers within 1e-6, else bilinear in the
    nodes present (None when a needed node is not in the table)."""
    rt, ra = round(t), round(a)
    if abs(t - rt) < 1e-6 and abs(a - ra) < 1e-6:
        return table.get((rt, ra)), "node"
    t0, a0 = int(math.floor(t)), int(math.floor(a))
    t1, a1 = min(t0 + 1, size - 1), min(a0 + 1, size - 1)
    ft, fa = t - t0, a - a0
    corners = [(t0, a0, (1 - ft) * (1 - fa)), (t1, a0, ft * (1 - fa)), (t0, a1, (1 - ft) * fa), (t1, a1, ft * fa)]
    m = np.zeros((3, 3))
    for ti, ai, w in corners:
        if w == 0.0:
            continue
        if (ti, ai) not in table:
            return None, "missing"
        m += w * table[(ti, ai)]
    return m, "interp"


def distance(mu, alpha, m, n):
    """(L1 distance, its quadrature error) or (nan, nan) for a singular M (an entry printed as
    0.000000 in the published file: alpha = 1e-4 at grazing)."""
    if abs(np.linalg.det(m)) < 1e-14:
        return float("nan"), float("nan")
    d, err, _ = ref.l1_distance_converged(max(mu, 1e-6), alpha, m, n)
    return d, err


def quad_errors(mu, alpha, m, count, rng):
    """[(relative error, error / E, within the total-variation bound, carries >= 1% of E)] of E x LTC polygon integral
    against the brute-force integral, for quads whose brute force has converged to 0.1%."""
    e = ref.lobe_terms(mu, alpha, 1024)[0]
    d, _, _ = ref.l1_distance_converged(mu, alpha, m, 128)
    bound = e * (d + 1 - ref.ltc_upper_mass(m)) / 2
    out = []
    for _ in range(count):
        corner, e1, e2 = ref.random_quad_light(rng)
        true, qerr = ref.quad_fcos_integral(mu, alpha, corner, e1, e2)
        if true <= 0 or qerr > 1e-3 * true:
            continue
        approx = e * ref.ltc_polygon_integral(m, np.array([corner, corner + e1, corner + e1 + e2, corner + e2]))
        out.append((abs(approx - true) / true, abs(approx - true) / e, abs(approx - true) <= bound + qerr,
                    true >= 0.01 * e))
    return out


def summary(name, values):
    v = np.array([x for x in values if np.isfinite(x)])
    if len(v) == 0:
        return "%s: none" % name
    return "%s over %d texels: min %.5f, median %.5f, max %.5f" % (name, len(v), v.min(), np.median(v), v.max())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("published")
    ap.add_argument("brdfbake_csv", nargs="?")
    ap.add_argument("--n", type=int, default=256)
    ap.add_argument("--every", type=int, default=1)
    ap.add_argument("--rows", default=None)
    ap.add_argument("--limit", type=int, default=0)
    ap.add_argument("--parametrisation", choices=("theta", "sqrt"), default=None,
                    help="the published file's view axis (default: theta for ltc.inc, sqrt for three.js)")
    ap.add_argument("--quads", type=int, default=0)
    ap.add_argument("--nodes-only", action="store_true",
                    help="compare only brdfbake texels that sit on a published texel (no interpolation)")
    args = ap.parse_args()
    table, size, parametrisation = read_published(args.published)
    if args.parametrisation is None:
        args.parametrisation = parametrisation

    if args.brdfbake_csv is None:
        rows = sorted(table)
        if args.rows:
            keep = {int(r) for r in args.rows.split(",")}
            rows = [k for k in rows if k[0] in keep]
        rows = [k for k in rows if k[1] % args.every == 0 or k[1] == size - 1]
        print("t a mu alpha d_published err" + (" quads rel_median rel_max err/E_max in_bound" if args.quads else ""))
        dists, rel, rel_e, inside = [], [], [], []
        rng = np.random.default_rng(33)
        for t, a in rows:
            mu, alpha = published_coordinates(t, a, size, args.parametrisation)
            d, err = distance(mu, alpha, table[(t, a)], args.n)
            dists.append(d)
            line = "%d %d %.6f %.6f %.5f %.1e" % (t, a, mu, alpha, d, err)
            if args.quads and alpha >= 0.02:
                q = quad_errors(max(mu, 1e-6), alpha, table[(t, a)], args.quads, rng)
                if q:
                    rel += [x[0] for x in q if x[3]]
                    rel_e += [x[1] for x in q]
                    inside += [x[2] for x in q]
                    line += " %d %.4f %.4f %.4f %d" % (len(q), np.median([x[0] for x in q]), max(x[0] for x in q),
                                                     max(x[1] for x in q), sum(x[2] for x in q))
            print(line, flush=True)
        print("# " + summary("published distance", dists))
        if rel:
            r, re_ = np.array(rel), np.array(rel_e)
            print("# quad lights: %d; error / E median %.5f, 90th percentile %.5f, max %.5f; relative error of the "
                  "%d carrying >= 1%% of E: median %.4f, 90th percentile %.4f, max %.4f; within the bound "
                  "E (L1 + 1 - c)/2: %d of %d" % (len(re_), np.median(re_), np.percentile(re_, 90), re_.max(), len(r),
                                                  np.median(r), np.percentile(r, 90), r.max(), sum(inside), len(inside)))
        return

    rows = read_brdfbake_csv(args.brdfbake_csv)
    if args.limit:
        rows = rows[: args.limit]
    print("mu alpha d_brdfbake err d_published err pub_at ratio d_file")
    ours, theirs, ratios = [], [], []
    for row in rows:
        mu, alpha = row["mu"], row["alpha"]
        m = ref.matrix_from_channels(row["m00"], row["m02"], row["m11"], row["m20"], row["m22"])
        d, err = distance(mu, alpha, m, args.n)
        t, a = published_index(mu, alpha, size, args.parametrisation)
        mp, where = published_matrix_at(table, size, t, a)
        if args.nodes_only and (where != "node" or mp is None):
            continue
        dp, errp = distance(mu, alpha, mp, args.n) if mp is not None else (float("nan"), float("nan"))
        ratio = d / dp if dp > 0 else float("nan")
        ours.append(d)
        theirs.append(dp)
        ratios.append(ratio)
        print("%.6f %.6f %.5f %.1e %.5f %.1e %s %.3f %s" % (mu, alpha, d, err, dp, errp, where, ratio,
                                                          "%.5f" % row["distance"] if "distance" in row else "-"),
              flush=True)
    print("# " + summary("brdfbake distance", ours))
    print("# " + summary("published distance", theirs))
    print("# " + summary("ratio brdfbake/published", ratios))


if __name__ == "__main__":
    main()
