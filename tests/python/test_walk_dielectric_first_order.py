"""The rough dielectric walk's first orders (`brdfbake albedo --model ggx|beckmann:...,scattering=multiple,
eta=E`: single_scattering R1 and single_scattering_transmitted T1) against an independent numpy
quadrature of the height-correlated rough dielectric interface, GGX and Beckmann: in half-vector space,
R1 = integral of D(h) <wo, h> / mu_o F(<wo, h>) / (1 + L(wo) + L(wr)) dh over the h whose mirror
direction wr lies above the surface, T1 = the same with 1 - F and the Beta function
B(1 + L(wo), 1 + L(-wt)) over the h whose refracted direction wt lies below [Heitz 2014 eq. 99 and
100; Walter et al. 2007 eq. 25, 27, 33, 40 for D, Lambda and the refraction], F the exact unpolarised
dielectric Fresnel term. Numpy and the executable only (BRDFBAKE_EXE); run by CTest's `python` test."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.environ.get("BRDFBAKE_EXE", os.path.join(ROOT, "build", "brdfbake"))

ERFC = np.vectorize(math.erfc)
LGAMMA = np.vectorize(math.lgamma)


def d_and_lambda(dist, alpha):
    if dist == "ggx":
        def d(cz, tan2):
            return 1 / (math.pi * alpha**2 * cz**4 * (1 + tan2 / alpha**2) ** 2)

        def lam(z):  # z = cos theta > 0 of a direction
            tan2 = np.maximum(1 - z * z, 0) / (z * z)
            return (-1 + np.sqrt(1 + alpha**2 * tan2)) / 2
    else:
        def d(cz, tan2):
            return np.exp(-tan2 / alpha**2) / (math.pi * alpha**2 * cz**4)

        def lam(z):
            a = z / (alpha * np.sqrt(np.maximum(1 - z * z, 1e-300)))
            return 0.5 * (np.exp(-a * a) / (a * math.sqrt(math.pi)) - ERFC(a))
    return d, lam


def fresnel(c, eta):
    s2 = (1 - c * c) / (eta * eta)
    ct = np.sqrt(np.maximum(1 - s2, 0))
    with np.errstate(invalid="ignore", divide="ignore"):  # c = 0 with total internal reflection: F = 1 below
        rs = (c - eta * ct) / (c + eta * ct)
        rp = (eta * c - ct) / (eta * c + ct)
    return np.where(s2 >= 1, 1.0, 0.5 * (rs * rs + rp * rp)), ct


def first_orders(dist, alpha, mu, eta, n_theta=600, n_phi=3000):
    d, lam = d_and_lambda(dist, alpha)
    wo = np.array([math.sqrt(1 - mu * mu), 0.0, mu])
    lo = float(lam(np.array([mu]))[0])
    # theta_h in panels split at atan(k alpha), Gauss-Legendre in each; phi by the midpoint rule on
    # [0, pi] (the integrand is even in phi), fine enough for the cuts (where wr or wt crosses the horizon).
    edges = [0.0] + [math.atan(k * alpha) for k in (1, 3, 10)] + [math.pi / 2]
    x, w = np.polynomial.legendre.leggauss(n_theta // 4)
    ths, wts = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        ths.append(0.5 * (a + b) + 0.5 * (b - a) * x)
        wts.append(0.5 * (b - a) * w)
    th, wt = np.concatenate(ths), np.concatenate(wts)
    ph = (np.arange(n_phi) + 0.5) * math.pi / n_phi
    TH, PH = np.meshgrid(th, ph, indexing="ij")
    h = np.stack([np.sin(TH) * np.cos(PH), np.sin(TH) * np.sin(PH), np.cos(TH)])
    c = wo[0] * h[0] + wo[2] * h[2]
    tan2 = np.tan(TH) ** 2
    vis = np.where(c > 0, d(h[2], tan2) * c / mu, 0.0) * np.sin(TH) * wt[:, None] * (2 * math.pi / n_phi)
    F, ct = fresnel(np.clip(c, 0, 1), eta)
    wr_z = 2 * c * h[2] - mu
    lr = lam(np.clip(wr_z, 1e-12, 1))
    r1 = np.sum(np.where(wr_z > 0, vis * F / (1 + lo + lr), 0.0))
    wt_z = -mu / eta + (c / eta - ct) * h[2]
    lt = lam(np.clip(-wt_z, 1e-12, 1))
    beta = np.exp(LGAMMA(1 + lo) + LGAMMA(1 + lt) - LGAMMA(2 + lo + lt))
    t1 = np.sum(np.where((wt_z < 0) & (F < 1), vis * (1 - F) * beta, 0.0))
    return r1, t1


def test_quadrature_conserves_the_smooth_limit():
    # At small alpha the first orders are the smooth interface's F(mu) and 1 - F(mu).
    for dist in ("ggx", "beckmann"):
        r1, t1 = first_orders(dist, 0.01, 0.7, 1.5, n_theta=400, n_phi=800)
        f = float(fresnel(np.array([0.7]), 1.5)[0][0])
        assert abs(r1 - f) < 2e-3 and abs(t1 - (1 - f)) < 2e-3, (dist, r1, t1, f)


@pytest.mark.parametrize("dist", ["ggx", "beckmann"])
def test_walk_first_orders_match_quadrature(dist):
    cells = [(0.3, 0.5, 1.5), (0.6, 0.8, 1 / 1.33), (0.9, 0.3, 1.33)]  # alpha, mu, eta
    for alpha, mu, eta in cells:
        out = subprocess.run([EXE, "albedo", "--model", f"{dist}:alpha={alpha},scattering=multiple,eta={eta:.6f}",
                              "--mu", str(mu), "--samples", "262144", "--format", "json"],
                             capture_output=True, text=True, timeout=300)
        assert out.returncode == 0, out.stderr
        v = json.loads(out.stdout)["results"][0]
        r1, t1 = first_orders(dist, alpha, mu, float(f"{eta:.6f}"))
        msg = f"{dist} alpha {alpha} mu {mu} eta {eta}: walk R1 {v['single_scattering']} T1 " \
              f"{v['single_scattering_transmitted']}, quadrature {r1} {t1}"
        # the walk's errors are 3 standard errors; 1e-4 for the quadrature (converged to 6e-6 here)
        assert abs(v["single_scattering"] - r1) <= v["single_scattering_error"] + 1e-4, msg
        assert abs(v["single_scattering_transmitted"] - t1) <= v["single_scattering_transmitted_error"] + 1e-4, msg
