#!/usr/bin/python3
"""The variance of diffuse=KD's one-sample mixture sampler for three choices of the Lambert chance c.

brdfbake samples f = f_spec + kd/pi of ggx:diffuse=KD (include/brdfbake/brdf/smith.h,
bb_smith_mixture_sample; sampling.h) by Veach's one-sample model with the balance heuristic: the
cosine warp with chance c, else GGX's visible-normal sample, the weight
W = f cos(theta_i) / p(wi), p = c cos(theta_i)/pi + (1 - c) pdf_lobe(wi). Its variance per sample is

    Var W = integral of (f cos / p - m)^2 p  +  m^2 (1 - c) P_lost,   m = E_spec + kd,

P_lost the chance that the lobe's sample reflects below the horizon (a weight of 0),

which this script integrates by deterministic quadrature (no noise): Gauss-Legendre in the
half-vector's radial CDF u = tan^2 / (alpha^2 + tan^2) (GGX's D cos measure: dw_h = du dphi /
(2 pi D cos theta_h)), the reflection's Jacobian 4 (wo.h), midpoints in phi. The chances compared:

  F : c = kd / (kd + F(cos theta_o)), brdfbake's choice (Fresnel at the viewer, no integral);
  E : c = kd / (kd + E(mu, alpha)), the lobe's own directional albedo (with its Fresnel);
  H : c = 1/2;
  and, for reference, the best c in (0, 1) (a golden-section search), which no cheap rule knows.

Everything here is independent of brdfbake's code: GGX D, height-correlated Smith G2 (brdfbake's
default ggx:shadowing=correlated), Schlick's Fresnel, written from Walter et al. 2007 and Heitz
2014/2018. A Monte Carlo cross-check (visible-normal sampling, Heitz 2018, "Sampling the GGX
Distribution of Visible Normals") at a few cells compares the sample variance with the quadrature's.

  mixture_variance.py [--nu N] [--nphi N] [--mc N]

Prints one row per (Fresnel, alpha, mu, kd): E_spec, the three chances, Var under each and the
ratios Var_F / Var_E, Var_F / Var_H, Var_F / Var_best; then the share of cells where E or 1/2
lowers the variance by more than 1.2x. Time: CPU seconds of this process.
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
import ltc_reference as ref  # noqa: E402


def ggx_d(cos_h, a):
    c2 = cos_h * cos_h
    return a * a / (np.pi * (c2 * (a * a - 1.0) + 1.0) ** 2)


def ggx_lambda(cos_t, a):
    c2 = np.clip(cos_t * cos_t, 1e-300, 1.0)
    t2 = (1.0 - c2) / c2
    return 0.5 * (np.sqrt(1.0 + a * a * t2) - 1.0)


def schlick(f0, cos_t):
    if f0 is None:
        return np.ones_like(cos_t)
    return f0 + (1.0 - f0) * (1.0 - cos_t) ** 5


class Cell:
    """Quadrature nodes for one (alpha, mu): wi, the measure and f_spec cos, pdf_lobe, cos_i."""

    def __init__(self, alpha, mu, f0, nu, nphi):
        x, w = np.polynomial.legendre.leggauss(nu)
        # u in [0, 1) in 8 graded panels (finer towards u = 1, where wi crosses the horizon).
        edges = 1.0 - np.geomspace(1.0, 1e-6, 9)
        edges[-1] = 1.0
        us, uw = [], []
        for lo, hi in zip(edges[:-1], edges[1:]):
            us.append(lo + (hi - lo) * (x + 1) / 2)
            uw.append(w * (hi - lo) / 2)
        u = np.concatenate(us)[:, None]
        wu = np.concatenate(uw)[:, None]
        phi = (np.arange(nphi) + 0.5) / nphi * 2 * np.pi
        t2 = alpha * alpha * u / (1.0 - u)
        cos_h = 1.0 / np.sqrt(1.0 + t2)
        sin_h = np.sqrt(np.clip(1.0 - cos_h * cos_h, 0, 1))
        h = np.stack([sin_h * np.cos(phi), sin_h * np.sin(phi), cos_h * np.ones_like(phi)])
        so = np.sqrt(1.0 - mu * mu)
        wo = np.array([so, 0.0, mu])
        oh = np.einsum("i,ijk->jk", wo, h)
        wi = 2 * oh[None] * h - wo[:, None, None]
        ci = wi[2]
        d = ggx_d(cos_h, alpha)
        measure = wu * (2 * np.pi / nphi) / (2 * np.pi * d * cos_h) * 4 * np.abs(oh)
        ok = (ci > 0) & (oh > 0)
        lo, li = ggx_lambda(mu, alpha), ggx_lambda(np.where(ok, ci, 1.0), alpha)
        g2 = 1.0 / (1.0 + lo + li)
        fspec_cos = np.where(ok, d * g2 * schlick(f0, np.clip(oh, 0, 1)) / (4 * mu), 0.0)
        self.pdf_lobe = np.where(ok, d / (1.0 + lo) / (4 * mu), 0.0)
        self.cos_i = np.where(ok, ci, 0.0)
        self.measure = np.where(ok, measure, 0.0)
        self.fspec_cos = fspec_cos
        self.e_spec = float(np.sum(fspec_cos * self.measure))
        self.f_view = float(schlick(f0, np.array(mu)))
        self.lambert_mass = float(np.sum(self.cos_i / np.pi * self.measure))  # 1 when converged
        # The chance that the lobe's sample reflects below the horizon (its weight is then 0).
        self.lobe_lost = max(0.0, 1.0 - float(np.sum(self.pdf_lobe * self.measure)))

    def variance(self, kd, c):
        f_cos = self.fspec_cos + kd / np.pi * self.cos_i
        p = c * self.cos_i / np.pi + (1.0 - c) * self.pdf_lobe
        # The integral of (W - mean)^2 p with the nodes' own mean (no cancellation between the
        # second moment and the squared mean), plus mean^2 times the chance of a weight of 0: a
        # lobe sample reflected below the horizon, (1 - c) times the lobe's mass lost there.
        w = np.where(p > 0, f_cos / np.where(p > 0, p, 1.0), 0.0)
        mean = float(np.sum(f_cos * self.measure))
        return float(np.sum((w - mean) ** 2 * p * self.measure) + mean * mean * (1.0 - c) * self.lobe_lost)


def best_chance(cell, kd):
    """The c in (0, 1) of least variance: Var is convex in c (the integral of (f cos)^2 / p, 1/p
    convex in p, p linear in c), so a golden-section search in logit(c) finds it."""
    lo, hi = -9.0, 9.0
    g = (np.sqrt(5) - 1) / 2
    var = lambda t: cell.variance(kd, 1.0 / (1.0 + np.exp(-t)))  # noqa: E731
    a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    va, vb = var(a), var(b)
    for _ in range(40):
        if va < vb:
            hi, b, vb = b, a, va
            a = hi - g * (hi - lo)
            va = var(a)
        else:
            lo, a, va = a, b, vb
            b = lo + g * (hi - lo)
            vb = var(b)
    t = a if va < vb else b
    return 1.0 / (1.0 + np.exp(-t)), min(va, vb)


def mc_variance(alpha, mu, f0, kd, c, n, rng):
    """The sample variance of the mixture's weight by n draws (the estimator brdfbake runs)."""
    wo = np.array([np.sqrt(1 - mu * mu), 0.0, mu])
    u1, u2 = rng.random(n), rng.random(n)
    lam = rng.random(n) < c
    r, ph = np.sqrt(1 - u1), 2 * np.pi * u2
    wl = np.stack([r * np.cos(ph), r * np.sin(ph), np.sqrt(u1)], axis=1)
    ws, _ = ref.vndf_sample(wo, alpha, u1, u2)  # tests/ltc_reference.py: Heitz 2018, listing 1
    wi = np.where(lam[:, None], wl, ws)
    ci = wi[:, 2]
    hh = wi + wo
    hh /= np.linalg.norm(hh, axis=1)[:, None]
    oh = hh @ wo
    ok = (ci > 0) & (oh > 0) & (hh[:, 2] > 0)
    d = ggx_d(hh[:, 2], alpha)
    lo, li = ggx_lambda(mu, alpha), ggx_lambda(np.where(ok, ci, 1.0), alpha)
    f_cos = np.where(ok, d / (1 + lo + li) * schlick(f0, np.clip(oh, 0, 1)) / (4 * mu) + kd / np.pi * ci, 0.0)
    pdf = np.where(ok, c * ci / np.pi + (1 - c) * d / (1 + lo) / (4 * mu), 0.0)
    wgt = np.where(pdf > 0, f_cos / np.where(pdf > 0, pdf, 1), 0.0)
    return wgt.mean(), wgt.var(ddof=1) / n, wgt.var(ddof=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--nu", type=int, default=96, help="Gauss-Legendre nodes per u panel (8 panels)")
    ap.add_argument("--nphi", type=int, default=384, help="midpoints in phi")
    ap.add_argument("--mc", type=int, default=1 << 21, help="Monte Carlo draws of the cross-check")
    args = ap.parse_args()
    t0 = time.process_time()
    alphas = [0.05, 0.1, 0.2, 0.4, 0.7, 1.0]
    mus = [0.1, 0.3, 0.5, 0.8, 1.0]
    kds = [0.05, 0.2, 0.5, 0.9]
    fresnels = [("none", None), ("schlick f0=0.04", 0.04)]
    rows = []
    print("fresnel alpha mu kd | E_spec lambert_mass | c_F c_E c_best | Var_F Var_E Var_H Var_best | "
          "F/E F/H F/best")
    worst_mass = 0.0
    for fname, f0 in fresnels:
        for a in alphas:
            for mu in mus:
                cell = Cell(a, mu, f0, args.nu, args.nphi)
                worst_mass = max(worst_mass, abs(cell.lambert_mass - 1.0))
                for kd in kds:
                    c_f = kd / (kd + cell.f_view)
                    c_e = kd / (kd + cell.e_spec)
                    v_f, v_e, v_h = cell.variance(kd, c_f), cell.variance(kd, c_e), cell.variance(kd, 0.5)
                    c_best, v_best = best_chance(cell, kd)
                    rows.append((fname, a, mu, kd, v_f, v_e, v_h, v_best))
                    print(f"{fname:16s} {a:4.2f} {mu:3.1f} {kd:4.2f} | {cell.e_spec:.5f} {cell.lambert_mass:.6f} | "
                          f"{c_f:.3f} {c_e:.3f} {c_best:.3f} | {v_f:.4e} {v_e:.4e} {v_h:.4e} {v_best:.4e} | "
                          f"{v_f / v_e:6.3f} {v_f / v_h:6.3f} {v_f / v_best:6.3f}")
    print(f"quadrature check: the Lambert part's mass integrates to 1 within {worst_mass:.2e} at every cell")
    r = np.array([[row[4] / row[5], row[4] / row[6], row[4] / row[7]] for row in rows])
    n = len(rows)
    for name, col in (("E", 0), ("1/2", 1), ("best c", 2)):
        g = r[:, col]
        print(f"c from {name:6s}: Var_F / Var = min {g.min():.3f}, median {np.median(g):.3f}, max {g.max():.3f}; "
              f"> 1.2 at {int(np.sum(g > 1.2))} of {n} cells, < 1/1.2 at {int(np.sum(g < 1 / 1.2))}")
    for fname, _ in fresnels:
        sel = np.array([row[0] == fname for row in rows])
        print(f"  {fname}: Var_F / Var_E median {np.median(r[sel, 0]):.3f} (max {r[sel, 0].max():.3f}), "
              f"Var_F / Var_H median {np.median(r[sel, 1]):.3f}, Var_F / Var_best median {np.median(r[sel, 2]):.3f} "
              f"(max {r[sel, 2].max():.3f})")
    rng = np.random.default_rng(7)
    print("Monte Carlo cross-check (mean, sample variance vs quadrature):")
    for a, mu, f0, kd in ((0.2, 0.5, None, 0.5), (0.05, 0.3, 0.04, 0.2), (0.7, 0.1, 0.04, 0.9)):
        cell = Cell(a, mu, f0, args.nu, args.nphi)
        c = kd / (kd + cell.f_view)
        mean, var_mean, var = mc_variance(a, mu, f0, kd, c, args.mc, rng)
        print(f"  alpha {a} mu {mu} f0 {f0} kd {kd} c_F {c:.3f}: mean {mean:.5f} +- {np.sqrt(var_mean):.5f} "
              f"(quadrature {cell.e_spec + kd:.5f}); variance {var:.4e} (quadrature {cell.variance(kd, c):.4e})")
    print(f"CPU {time.process_time() - t0:.1f} s")


if __name__ == "__main__":
    main()
