"""`brdfbake compensation --furnace` (issue 35 item 6): the furnace picture of single,
compensated and multiple scattering side by side, decoded and held to outside truths. In the
white furnace (Schlick f0 = 1) every compensation scheme is exact by construction (Kulla and
Conty 2017, Fdez-Aguera 2019, Turquin 2019) and the random walk loses no energy (Heitz et al.
2016): their spheres are white. The single-scattering sphere shows the height-correlated GGX
albedo E(mu), here by a numpy quadrature of D G2 / (4 mu_o mu_i) (Heitz 2014 eq. 99) over the
hemisphere, at the last of the picture's mu nodes ((k + 0.5)/n)^2, which the sphere's centre holds.

Numpy and the executable only (BRDFBAKE_EXE); run by CTest's `python` test."""
import os
import subprocess

import numpy as np

from test_fresnel_rgb import EXE, read_png_rgb


def ggx_albedo(mu_o, alpha, n=400):
    """E(mu_o) of height-correlated GGX with F = 1, midpoint rule in (theta_i, phi_i)."""
    t = (np.arange(n) + 0.5) / n * np.pi / 2
    ph = (np.arange(2 * n) + 0.5) / (2 * n) * 2 * np.pi
    T, P = np.meshgrid(t, ph, indexing="ij")
    wi = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], -1)
    wo = np.array([np.sqrt(1 - mu_o ** 2), 0.0, mu_o])
    h = wi + wo
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    a2 = alpha * alpha
    D = a2 / (np.pi * (h[..., 2] ** 2 * (a2 - 1) + 1) ** 2)
    lam = lambda c: (-1 + np.sqrt(1 + a2 * (1 - c * c) / (c * c))) / 2
    G2 = 1 / (1 + lam(mu_o) + lam(wi[..., 2]))
    f = D * G2 / (4 * mu_o * wi[..., 2])
    return float(np.sum(f * wi[..., 2] * np.sin(T)) * (np.pi / 2 / n) * (np.pi / n))


def test_white_furnace_spheres(tmp_path):
    path = str(tmp_path / "furnace.png")
    alphas, nodes = (0.5, 1.5), 8
    out = subprocess.run([EXE, "compensation", "--f0", "1", "--alpha", ",".join(map(str, alphas)), "--mu", "1",
                          "--walks", "4096", "--lobe-directions", "0", "--furnace", path, "--furnace-nodes",
                          str(nodes), "--furnace-pixels", "60"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    pixels = read_png_rgb(path)
    height, width = pixels.shape[:2]
    columns = 5  # single, kulla-conty, fdez-aguera, turquin, walk
    panel_w = (width - 200) / columns  # the colour bar's strip is 200 pixels wide
    panel_h = (1 - 0.06 / len(alphas)) / len(alphas) * height  # the caption's strip below
    mu_last = ((nodes - 0.5) / nodes) ** 2
    for row, alpha in enumerate(alphas):
        levels = []
        for column in range(columns):
            # The sphere's centre: the middle of the panel across, 0.55 of it down (the title above).
            x, y = int(panel_w * (column + 0.5)), int(panel_h * (row + 0.55))
            patch = pixels[y - 2:y + 3, x - 2:x + 3].reshape(-1, 3)
            assert np.all(patch == patch[0]), (alpha, column, patch)  # one flat grey
            assert patch[0][0] == patch[0][1] == patch[0][2], (alpha, column, patch[0])
            levels.append(int(patch[0][0]))
        # White (MathGL shades white as 252) for the schemes and the walk.
        assert all(level >= 249 for level in levels[1:]), (alpha, levels)
        # The single-scattering sphere: 255 E(mu) less MathGL's shading (a couple of levels).
        e = ggx_albedo(mu_last, alpha)
        assert abs(levels[0] - 255 * e) <= 4, (alpha, levels[0], 255 * e)
        assert levels[0] < 240, (alpha, levels)  # the energy single scattering loses shows


def test_furnace_refusals(tmp_path):
    for args, word in ((["--furnace", str(tmp_path / "a.txt")], "--furnace"),
                       (["--furnace", str(tmp_path / "a.png"), "--furnace-nodes", "2"], "--furnace-nodes"),
                       (["--furnace", str(tmp_path / "a.png"), "--plot", str(tmp_path / "a.png")], "same file"),
                       (["--model", "ggx:eta=1.5", "--furnace", str(tmp_path / "a.png")], "dielectric")):
        out = subprocess.run([EXE, "compensation"] + args, capture_output=True, text=True)
        assert out.returncode == 2 and out.stderr.startswith("brdfbake: error:") and word in out.stderr, (args, out.stderr)
        assert out.stderr.count("\n") == 1 and not os.path.exists(str(tmp_path / "a.png"))
