#!/usr/bin/python3
"""Which LTC is closer to the simulated sheen lobe: brdfbake's or Cycles' table_sheen_ltc?

An independent NumPy random walk through the fiber SGGX layer of Zeltner, Burley and Chiang 2022
(unit thickness, density 1, albedo 1, S = diag(1, 1, sigma^2), sigma = roughness^2; Heitz et al.
2015 eqs. 8, 9 for the projected area and the visible normals, written from the equations, not from
brdfbake's kernel) histograms the exit directions through the top in 32 x 32 bins (theta in
[0, pi/2], |phi| in [0, pi]). The first flight is forced to collide inside the layer (weight
1 - exp(-sigma(wo)/mu)), which changes no expectation and makes the near-normal views affordable.

Per texel (row j = roughness j/31, column i = mu i/31, both floored at 0.01 as the paper's fit):
  R_sim          the reflectance (and its standard error over 8 replicas),
  L1(ours)       integral |lobe/R - D_ltc| over the hemisphere, D_ltc averaged over each bin
                 (4 x 4 sub-points), for brdfbake's LTC (a CSV of `lut sheen-ltc --preset cycles`),
  L1(Cycles)     the same for Cycles' shipped (A, B),
  L1(best)       the same for the LTC that minimises it (scipy Nelder-Mead from both starts),
  floor          the histogram's noise floor in an L1 (sqrt(2/pi) standard errors per bin, summed),
  L3 ratio       the paper's own objective (sum of |R D_ltc - lobe|^3 at the 32 x 32 bin centres, R the
                 simulated one for both) of our LTC over Cycles': below 1 where ours fits better by it.
--bounces 16 imitates the paper's public precomputation (maxBounces = 16; a walk stopped after its
16th scattering counts as reflected when its direction points up); the default is 1000 (brdfbake's).

Usage: sheen_lobe_vs_sim.py OURS.csv CYCLES_ROWS.py --texels J:I,J:I,... [--walks N] [--bounces B]
CYCLES_ROWS.py is a transcription kept outside the repository (dicts A, B, R: row j -> 32 values).
Needs NumPy and SciPy (Debian python3-numpy, python3-scipy; no test uses this script). 4e6 walks take
~20 s of one core a texel. Figures: benchmarks/results/sheen-ltc-amd-epyc-2c.md (session 5).
"""
import argparse
import runpy

import numpy as np
from scipy.optimize import minimize

NT, NP, SUB, REPS = 32, 32, 4, 8


def area(w, s):
    """Projected area of the fiber SGGX, sqrt(w^T S w) [HDCD15 eq. 9]."""
    return np.sqrt(w[:, 0] ** 2 + w[:, 1] ** 2 + (s * w[:, 2]) ** 2)


def visible_normal(v, s, u1, u2):
    """A normal m with density <v, m>+ D(m) / sigma(v): the ellipsoid x^T S x = 1 is the unit sphere
    stretched by diag(1, 1, 1/s); a uniform point of the disk across the stretched view is lifted onto
    the sphere and its normal mapped back by diag(1, 1, s)."""
    vs = v * np.array([1.0, 1.0, s])
    vs /= np.linalg.norm(vs, axis=1)[:, None]
    # an orthonormal basis (t1, t2, vs): t1 perpendicular to vs in the plane of vs and the z axis
    helper = np.where(np.abs(vs[:, 2:3]) < 0.999, np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0]))
    t1 = np.cross(helper, vs)
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    t2 = np.cross(vs, t1)
    r, phi = np.sqrt(u1), 2.0 * np.pi * u2
    d1, d2 = r * np.cos(phi), r * np.sin(phi)
    lift = np.sqrt(np.maximum(0.0, 1.0 - d1 * d1 - d2 * d2))
    p = t1 * d1[:, None] + t2 * d2[:, None] + vs * lift[:, None]
    m = p * np.array([1.0, 1.0, s])
    return m / np.linalg.norm(m, axis=1)[:, None]


def walk(mu, rough, n, bounces, rng):
    """Directions of the walks leaving through the top and the weight each carries."""
    s = rough * rough
    wo = np.array([np.sqrt(1.0 - mu * mu), 0.0, mu])
    ko = area(wo[None, :], s)[0] / mu
    weight = -np.expm1(-ko)
    w = np.tile(-wo, (n, 1))
    # first flight forced inside: depth ~ Exp(ko) truncated to [0, 1]
    t = -np.log1p(-rng.random(n) * weight) / ko
    out = []
    for k in range(1, bounces + 1):
        v = -w
        m = visible_normal(v, s, rng.random(len(w)), rng.random(len(w)))
        w = 2.0 * np.sum(v * m, axis=1)[:, None] * m - v
        w /= np.linalg.norm(w, axis=1)[:, None]
        if k == bounces:  # stopped: the paper's precomputation counts an upward direction as reflected
            out.append(w[w[:, 2] > 0.0] if bounces < 1000 else w[:0])
            break
        t = t - (-np.log1p(-rng.random(len(w))) / area(w, s)) * w[:, 2]
        top = t < 0.0
        out.append(w[top])
        keep = (t >= 0.0) & (t <= 1.0)
        w, t = w[keep], t[keep]
        if len(w) == 0:
            break
    return np.concatenate(out), weight


def bin_solid_angles():
    th = np.linspace(0.0, 0.5 * np.pi, NT + 1)
    return (np.cos(th[:-1]) - np.cos(th[1:]))[:, None] * (2.0 * np.pi / NP) * np.ones((1, NP))


def histogram(dirs, n, weight):
    th = np.arccos(np.clip(dirs[:, 2], 0.0, 1.0))
    ph = np.abs(np.arctan2(dirs[:, 1], dirs[:, 0]))
    h, _, _ = np.histogram2d(th, ph, bins=[NT, NP], range=[[0.0, 0.5 * np.pi], [0.0, np.pi]])
    return h * weight / (n * bin_solid_angles())


def sub_points():
    f = (np.arange(SUB) + 0.5) / SUB
    th = ((np.arange(NT)[:, None] + f[None, :]) * 0.5 * np.pi / NT).reshape(-1)
    ph = ((np.arange(NP)[:, None] + f[None, :]) * np.pi / NP).reshape(-1)
    T, P = np.meshgrid(th, ph, indexing="ij")
    return np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T), np.sin(T)


SP = sub_points()


def ltc_bins(a, b):
    """The LTC density (Heitz et al. 2016 eq. 1) averaged over each bin (sin-weighted sub-points)."""
    x, y, z, st = SP
    u, v = a * x + b * z, a * y
    nn = np.sqrt(u * u + v * v + z * z)
    d = np.maximum(z / nn, 0.0) / np.pi * a * a / nn**3
    num = (d * st).reshape(NT, SUB, NP, SUB).sum(axis=(1, 3))
    den = st.reshape(NT, SUB, NP, SUB).sum(axis=(1, 3))
    return num / den


def centres():
    th = (np.arange(NT) + 0.5) * 0.5 * np.pi / NT
    ph = (np.arange(NP) + 0.5) * np.pi / NP
    T, P = np.meshgrid(th, ph, indexing="ij")
    return np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)


CP = centres()


def l3(lobe, r, a, b):
    """The paper's objective: sum over the 32 x 32 bin centres of |R D_ltc - lobe|^3 (unnormalised)."""
    x, y, z = CP
    u, v = a * x + b * z, a * y
    nn = np.sqrt(u * u + v * v + z * z)
    return float(np.sum(np.abs(r * np.maximum(z / nn, 0.0) / np.pi * a * a / nn**3 - lobe) ** 3))


def l1(p, a, b):
    if not (a > 0.0):
        return float("nan")
    return float(np.sum(np.abs(p - ltc_bins(a, b)) * bin_solid_angles()))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("ours")
    ap.add_argument("cycles")
    ap.add_argument("--texels", required=True)
    ap.add_argument("--walks", type=int, default=2_000_000)
    ap.add_argument("--bounces", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    lines = [ln for ln in open(args.ours) if not ln.startswith("#")]
    cols = lines[0].strip().split(",")
    ours = [dict(zip(cols, map(float, ln.split(",")))) for ln in lines[1:]]
    ref = runpy.run_path(args.cycles)
    rng = np.random.default_rng(args.seed)
    print(f"walks {args.walks} a texel ({REPS} replicas), bounce limit {args.bounces}")
    print("| j (r) | i (mu) | R_sim | R ours | R Cycles | L1 ours | L1 Cycles | L1 best (a, b) | floor | L3 ours / L3 Cycles |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for tx in args.texels.split(","):
        j, i = (int(x) for x in tx.split(":"))
        mu, rough = max(i / 31, 0.01), max(j / 31, 0.01)
        reps = []
        for _ in range(REPS):
            dirs, wgt = walk(mu, rough, args.walks // REPS, args.bounces, rng)
            reps.append(histogram(dirs, args.walks // REPS, wgt))
        reps = np.array(reps)
        lobe = reps.mean(axis=0)
        r_reps = (reps * bin_solid_angles()).sum(axis=(1, 2))
        r_sim = lobe.ravel() @ bin_solid_angles().ravel()
        p = lobe / r_sim
        se = reps.std(axis=0, ddof=1) / np.sqrt(REPS) / r_sim
        floor = float(np.sum(np.sqrt(2.0 / np.pi) * se * bin_solid_angles()))
        row = ours[j * 32 + i]
        a, b, ra, rb = row["a"], row["b"], ref["A"][j][i], ref["B"][j][i]
        l_ours, l_cyc = l1(p, a, b), l1(p, ra, rb)
        best = min((minimize(lambda x: l1(p, np.exp(x[0]), x[1]), [np.log(max(s0[0], 1e-3)), s0[1]],
                             method="Nelder-Mead", options={"xatol": 1e-5, "fatol": 1e-7, "maxiter": 2000})
                    for s0 in ((a, b), (ra, rb) if ra > 0 else (a, b))), key=lambda m: m.fun)
        print(f"| {j} ({j/31:.3f}) | {i} ({i/31:.3f}) | {r_sim:.5f} ± {r_reps.std(ddof=1)/np.sqrt(REPS):.1e} "
              f"| {row['R']:.5f} | {ref['R'][j][i]:.5f} | {l_ours:.3f} (a {a:.4f}, b {b:.4f}) "
              f"| {l_cyc:.3f} (a {ra:.4f}, b {rb:.4f}) | {best.fun:.3f} ({np.exp(best.x[0]):.4f}, {best.x[1]:.4f}) "
              f"| {floor:.3f} | {l3(lobe, r_sim, a, b) / l3(lobe, r_sim, ra, rb):.2f} |", flush=True)


if __name__ == "__main__":
    main()
