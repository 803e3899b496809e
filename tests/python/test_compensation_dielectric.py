"""`brdfbake compensation --eta E` (issue 35 item 3, the rough dielectric): the compensation schemes of
rough glass against the dielectric random walk, held to truths from outside the code:

- the single-scattering R and T the schemes are built from equal an independent numpy quadrature of
  the height-correlated GGX interface (Heitz 2014 eq. 99 and 100, test_walk_dielectric_first_order.py);
- Turquin 2019 scales the whole BSDF by 1/E: its R is R1 / (R1 + T1) of that quadrature;
- Kulla and Conty 2017 ("Dielectrics"): the lost energy 1 - E is split into reflection and transmission
  by the shares 1 - tau and tau, tau = (1 - Favg) x from outside and (1 - Favg') (1 - x) from inside,
  x balancing the energy carried through the interface as a smooth interface does (the cosine-weighted
  transmittance from inside is that from outside over eta^2); here Favg from numpy quadrature of the
  Fresnel equations and Eavg = 2 int (R1 + T1) mu dmu from the numpy quadrature;
- both schemes, and the walk, conserve energy: R + T = 1 from both sides (non-absorbing interface);
- the smooth limit (alpha -> 0): every scheme's and the walk's R is Fresnel's F(mu), total internal
  reflection (R = 1) from inside beyond the critical angle; the limit eta -> 1 (no interface): the
  walk's R and Turquin's vanish, Kulla and Conty's symmetric split (x = 1/2) reflects half the loss;
- the furnace picture: the scheme and walk spheres white, the single sphere 255 (R1 + T1) of numpy;
- bad input refused in one line (exit 2, nothing written).

Numpy and the executable only (BRDFBAKE_EXE); run by CTest's `python` test."""
import json
import math
import subprocess

import numpy as np
import pytest

from test_fresnel_rgb import read_png_rgb
from test_walk_dielectric_first_order import EXE, first_orders, fresnel

ETA = 1.5


def run(*args, timeout=300):
    return subprocess.run([EXE, "compensation", *args], capture_output=True, text=True, timeout=timeout)


def compensation(alpha, mus, walks=16384, extra=()):
    out = run("--eta", str(ETA), "--alpha", str(alpha), "--mu", ",".join(map(str, mus)), "--walks", str(walks),
              "--lobe-directions", "0", "--format", "json", *extra)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)["results"]


def fresnel_average(eta, n=200):
    """Favg = 2 int_0^1 F(mu) mu dmu: 2 int_0^mu_c mu dmu = mu_c^2 under total internal reflection
    (eta < 1), Gauss-Legendre in u on the rest, mu = mu_c + (1 - mu_c) u^2 (F's square root at mu_c)."""
    mu_c = math.sqrt(1 - eta * eta) if eta < 1 else 0.0
    x, w = np.polynomial.legendre.leggauss(n)
    u, wu = 0.5 + 0.5 * x, 0.5 * w
    mu = mu_c + (1 - mu_c) * u * u
    return mu_c**2 + float(np.sum(wu * 2 * (1 - mu_c) * u * 2 * mu * fresnel(mu, eta)[0]))


def albedo_average(alpha, eta, nodes=16):
    """Eavg = 2 int_0^1 (R1 + T1)(mu) mu dmu by Gauss-Legendre over mu, R1 and T1 from numpy."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    mus, ws = 0.5 + 0.5 * x, 0.5 * w
    return float(sum(wk * 2 * m * sum(first_orders("ggx", alpha, m, eta, n_theta=120, n_phi=400))
                     for m, wk in zip(mus, ws)))


def test_fresnel_average_identity():
    # The quadrature itself: the smooth interface's transmittance from inside is that from outside / eta^2.
    assert abs((1 - fresnel_average(1 / ETA)) - (1 - fresnel_average(ETA)) / ETA**2) < 1e-9


def test_schemes_against_quadrature_both_sides():
    alpha, mus = 0.5, (0.3, 0.8)
    rows = compensation(alpha, mus)
    assert len(rows) == 2 * len(mus)
    f_avg = {"outside": fresnel_average(ETA), "inside": fresnel_average(1 / ETA)}
    e_avg = {"outside": albedo_average(alpha, ETA), "inside": albedo_average(alpha, 1 / ETA)}
    # Kulla and Conty's split from the numpy Eavg and Favg.
    t = ETA**2 * (1 - e_avg["inside"]) * (1 - f_avg["inside"]) / ((1 - e_avg["outside"]) * (1 - f_avg["outside"]))
    x = t / (1 + t)
    tau = {"outside": (1 - f_avg["outside"]) * x, "inside": (1 - f_avg["inside"]) * (1 - x)}
    for v in rows:
        side = v["side"]
        eta = ETA if side == "outside" else 1 / ETA
        msg = f"{side} mu {v['mu']}: {v}"
        r1, t1 = first_orders("ggx", alpha, v["mu"], eta, n_theta=240, n_phi=900)  # within 5e-5 of 600 x 3000
        assert abs(v["single_R"] - r1) <= v["input_error"] + 2e-4, msg
        assert abs(v["single_T"] - t1) <= v["input_error"] + 2e-4, msg
        assert abs(v["e_avg"] - e_avg[side]) < 1e-3, (msg, e_avg[side])
        assert abs(v["f_avg"] - f_avg[side]) < 1e-9, (msg, f_avg[side])
        # (Each scheme's R + T and the walk's are 1 by construction: E plus the 1 - E put back, R_ss/E + T_ss/E,
        # every walk ending above or below. Not asserted: such a check cannot fail. What can is below.)
        # Turquin 2019: the single-scattering BSDF over E.
        assert abs(v["turquin_R"] - r1 / (r1 + t1)) < 1e-3, msg
        # Kulla and Conty 2017: the lost energy split by tau.
        assert abs(v["kulla-conty_T"] - (t1 + (1 - r1 - t1) * tau[side])) < 2e-3, (msg, tau[side])
        assert abs(v["kulla_conty_transmitted_share"] - tau[side]) < 5e-3, (msg, tau[side])
    # The balance the split is built on, between the reported sides (exact by construction of x).
    out, ins = rows[0], rows[len(mus)]
    lhs = (1 - out["e_avg"]) * out["kulla_conty_transmitted_share"] / ETA**2
    rhs = (1 - ins["e_avg"]) * ins["kulla_conty_transmitted_share"]
    assert abs(lhs - rhs) <= 1e-12 * max(lhs, rhs), (lhs, rhs)


def test_smooth_limit_is_fresnel():
    # At alpha 0.01 nothing is lost: every scheme's R and the walk's are the smooth interface's F(mu);
    # from inside at mu 0.3 (beyond the critical angle, mu_c = 0.745) total internal reflection, R = 1.
    mus = (0.3, 0.9)
    for v in compensation(0.01, mus, walks=4096):
        eta = ETA if v["side"] == "outside" else 1 / ETA
        f = float(fresnel(np.array([v["mu"]]), eta)[0][0])
        for s in ("kulla-conty", "turquin"):
            assert abs(v[f"{s}_R"] - f) < 2e-3, (s, v, f)
        assert abs(v["walk_R"] - f) <= v["walk_R_error"] + 2e-3, (v, f)


def test_no_interface_limit():
    # eta -> 1: no interface, R = 0 and T = 1 (the walk's; the single-scattering T is small at grazing
    # because the Smith microsurface stops a straight-through path: later orders carry it). Turquin's
    # R = R_ss / E keeps R_ss's vanishing share; Kulla and Conty's split is symmetric at eta = 1
    # (Favg = Favg' = 0, Eavg = Eavg': the balance gives x = 1 - x = 1/2), so half the lost energy is
    # reflected: R = R_ss + (1 - E) / 2.
    eta = 1.001
    out = run("--eta", str(eta), "--alpha", "1", "--mu", "0.1,1", "--walks", "16384", "--lobe-directions", "0",
              "--format", "json")
    assert out.returncode == 0, out.stderr
    for v in json.loads(out.stdout)["results"]:
        # below 0.005: from inside, total reflection at grazing microfacets (beyond mu_c = 0.045) remains
        assert v["walk_R"] <= v["walk_R_error"] + 5e-3, v
        assert v["turquin_R"] < 5e-3 + v["walk_R"], v
        lost = 1 - v["single_R"] - v["single_T"]
        # within 0.5% of the loss: Favg' = 0.0023 from inside at eta 1.001 (total reflection at grazing)
        assert abs(v["kulla-conty_R"] - (v["single_R"] + lost / 2)) < 5e-3 * lost, v


def test_furnace_picture(tmp_path):
    path = str(tmp_path / "glass.png")
    nodes, alpha = 8, 1
    out = run("--eta", str(ETA), "--alpha", str(alpha), "--mu", "1", "--walks", "4096", "--lobe-directions", "0",
              "--furnace", path, "--furnace-nodes", str(nodes), "--furnace-pixels", "60")
    assert out.returncode == 0, out.stderr
    pixels = read_png_rgb(path)
    height, width = pixels.shape[:2]
    columns, rows = 4, 2  # single, kulla-conty, turquin, walk; outside, inside
    panel_w, panel_h = (width - 200) / columns, (1 - 0.06 / rows) / rows * height
    mu_last = ((nodes - 0.5) / nodes) ** 2
    for row, eta in enumerate((ETA, 1 / ETA)):
        levels = []
        for column in range(columns):
            x, y = int(panel_w * (column + 0.5)), int(panel_h * (row + 0.55))
            patch = pixels[y - 2:y + 3, x - 2:x + 3].reshape(-1, 3)
            assert np.all(patch == patch[0]), (row, column, patch)
            levels.append(int(patch[0][0]))
        assert all(level >= 249 for level in levels[1:]), (row, levels)
        e = sum(first_orders("ggx", alpha, mu_last, eta, n_theta=240, n_phi=900))
        assert abs(levels[0] - 255 * e) <= 4, (row, levels[0], 255 * e)


@pytest.mark.parametrize("args, says", [
    (["--eta", "1"], "--eta: 1 must lie in (1, 4]"),
    (["--eta", "1.5", "--model", "beckmann"], "--model 'beckmann' with --eta"),
    (["--eta", "1.5", "--f0", "0.3"], "--f0 with --eta"),
    (["--eta", "1.5", "--scheme", "fdez-aguera"], "defines no transmission"),
    (["--eta", "1.5", "--mu", "0"], "--mu: 0 must lie in (0, 1]"),
])
def test_bad_input_one_line(tmp_path, args, says):
    path = tmp_path / "out.txt"
    out = run(*args, "-o", str(path))
    assert out.returncode == 2, out
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("brdfbake: error: ") and says in lines[0], out.stderr
    assert not path.exists()
