"""`brdfbake fresnel --rgb` (issue 36) against an independent numpy computation: the CIE 1931
observer and D65 read from data/cie, the IEC 61966-2-1 XYZ -> linear sRGB matrix as the standard
prints it (4 decimals), n, k of data/nk linearly interpolated, and the exact Fresnel reflectance
in numpy complex arithmetic (Born & Wolf 1.5.2 with a complex index). Also: a constant spectrum
is its own colour (a dielectric's F does not depend on the wavelength here).

Numpy and the executable only (BRDFBAKE_EXE); run by CTest's `python` test."""
import json
import os
import subprocess

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.environ.get("BRDFBAKE_EXE", os.path.join(ROOT, "build", "brdfbake"))

# IEC 61966-2-1:1999 (sRGB), XYZ (D65, Y = 1) -> linear RGB, as printed in the standard.
IEC_SRGB = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])


def read_csv(name):
    return np.loadtxt(os.path.join(ROOT, "data", "cie", name), delimiter=",", comments="#", skiprows=3)


def colour_weights():
    cmf = read_csv("cie1931_2deg_1nm.csv")
    d65 = read_csv("cie_d65.csv")
    nm = np.arange(380, 781)
    xyz = np.array([np.interp(nm, cmf[:, 0], cmf[:, c]) for c in (1, 2, 3)])
    e = np.interp(nm, d65[:, 0], d65[:, 1])
    w = xyz * e
    return nm, w / w[1].sum()


def read_nk(name):
    rows = []
    with open(os.path.join(ROOT, "data", "nk", name)) as f:
        inside = False
        for line in f:
            if "data: |" in line:
                inside = True
                continue
            if inside:
                parts = line.split()
                if len(parts) != 3:
                    break
                rows.append([float(p) for p in parts])
    return np.array(rows)


def fresnel_exact(cos_i, n):
    """Unpolarised reflectance from air onto complex index n (Born & Wolf 1.5.2, 14.2)."""
    sin2 = 1.0 - cos_i ** 2
    ct = np.sqrt(n * n - sin2 + 0j)  # n cos_t
    ct = np.where(ct.imag < 0, -ct, ct)
    rs = (cos_i - ct) / (cos_i + ct)
    rp = (n * n * cos_i - ct) / (n * n * cos_i + ct)
    return 0.5 * (abs(rs) ** 2 + abs(rp) ** 2)


def run_rgb(spec, thetas, colour_space="srgb"):
    out = subprocess.run([EXE, "fresnel", "--fresnel", spec, "--rgb", "--precision", "double", "--format", "json",
                          "--colour-space", colour_space, "--theta", ",".join(str(t) for t in thetas)],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)["results"]


def test_white_point_of_d65_under_the_1931_observer():
    _, w = colour_weights()
    X, Y, Z = w.sum(axis=1)
    assert abs(X / (X + Y + Z) - 0.3127) < 1e-4 and abs(Y / (X + Y + Z) - 0.3290) < 1e-4


@pytest.mark.parametrize("metal", ["Au", "Cu", "Ag", "Al"])
def test_metal_colour_matches_numpy(metal):
    files = {"Au": "Au-Johnson.yml", "Cu": "Cu-Johnson.yml", "Ag": "Ag-Johnson.yml", "Al": "Al-Rakic.yml"}
    nk = read_nk(files[metal])
    nm, w = colour_weights()
    n = np.interp(nm * 1e-3, nk[:, 0], nk[:, 1]) + 1j * np.interp(nm * 1e-3, nk[:, 0], nk[:, 2])
    thetas = [0, 45, 80, 89]
    for r, theta in zip(run_rgb("metal:" + metal, thetas), thetas):
        F = fresnel_exact(np.cos(np.radians(theta)), n)
        rgb = IEC_SRGB @ (w @ F)
        # The standard's matrix is printed to 4 decimals: ~1e-4 of a channel; the program's error
        # channel (1 nm against 2 nm sums) is added.
        tol = 2e-3 + np.array(r["rgb_error"])
        assert np.all(np.abs(np.array(r["rgb"]) - rgb) <= tol), (metal, theta, r["rgb"], rgb)


def xyz_to_rgb(primaries, white_xy):
    """XYZ -> RGB of the chromaticities (SMPTE RP 177): the primaries scaled to sum to the white."""
    xyz = lambda x, y: np.array([x / y, 1.0, (1.0 - x - y) / y])
    p = np.column_stack([xyz(*c) for c in primaries])
    return np.linalg.inv(p * np.linalg.solve(p, xyz(*white_xy)))


# Bradford (Lam 1985), as ICC.1:2010 Annex E prints it.
BRADFORD = np.array([[0.8951, 0.2664, -0.1614], [-0.7502, 1.7135, 0.0367], [0.0389, -0.0685, 1.0296]])


@pytest.mark.parametrize("metal", ["Au", "Cu"])
def test_acescg_colour_matches_numpy(metal):
    """--colour-space acescg: the spectral colour in AP1 (S-2014-004) with the ACES white
    (TB-2018-001), adapted from D65 by Bradford; numpy from the chromaticities alone."""
    files = {"Au": "Au-Johnson.yml", "Cu": "Cu-Johnson.yml"}
    nk = read_nk(files[metal])
    nm, w = colour_weights()
    n = np.interp(nm * 1e-3, nk[:, 0], nk[:, 1]) + 1j * np.interp(nm * 1e-3, nk[:, 0], nk[:, 2])
    d65 = w.sum(axis=1)  # the sums' own white (x, y within 1e-4 of D65's)
    aces = np.array([0.32168 / 0.33767, 1.0, (1 - 0.32168 - 0.33767) / 0.33767])
    cone = BRADFORD @ aces / (BRADFORD @ d65)
    adapt = np.linalg.inv(BRADFORD) @ np.diag(cone) @ BRADFORD
    ap1 = xyz_to_rgb([(0.713, 0.293), (0.165, 0.830), (0.128, 0.044)], (0.32168, 0.33767))
    for r, theta in zip(run_rgb("metal:" + metal, [0, 60, 85], "acescg"), [0, 60, 85]):
        F = fresnel_exact(np.cos(np.radians(theta)), n)
        rgb = ap1 @ adapt @ (w @ F)
        assert np.all(np.abs(np.array(r["rgb"]) - rgb) <= 1e-9 + np.array(r["rgb_error"])), (metal, theta, r["rgb"], rgb)
    # White stays white, and a constant spectrum its own value, in ACEScg too.
    r = run_rgb("dielectric:eta=1.5", [0, 70], "acescg")
    for res, theta in zip(r, [0, 70]):
        F = fresnel_exact(np.cos(np.radians(theta)), 1.5 + 0j)
        assert np.all(np.abs(np.array(res["rgb"]) - F) < 1e-12), (theta, res["rgb"], F)


def test_constant_spectrum_is_its_own_colour():
    thetas = [0, 30, 60, 85]
    for r, theta in zip(run_rgb("dielectric:eta=1.5", thetas), thetas):
        F = fresnel_exact(np.cos(np.radians(theta)), 1.5 + 0j)
        assert np.all(np.abs(np.array(r["rgb"]) - F) < 1e-12), (theta, r["rgb"], F)


def test_gold_is_yellow_and_silver_near_white():
    au = run_rgb("metal:Au", [0])[0]["rgb"]
    ag = run_rgb("metal:Ag", [0])[0]["rgb"]
    assert au[0] > au[1] > au[2]
    assert max(ag) - min(ag) < 0.1


def run_fit(spec):
    out = subprocess.run([EXE, "fresnel", "--fresnel", spec, "--fit", "f82-tint", "--precision", "double",
                          "--format", "json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def f82_tint(mu, f0, tint):
    """F82-tint (Kutz et al. 2021): Schlick less b mu (1 - mu)^6 with F(1/7) = tint * Schlick(1/7)."""
    schlick = lambda m: f0 + (1 - f0) * (1 - m) ** 5
    mb = 1.0 / 7.0
    b = (1 - tint) * schlick(mb) / (mb * (1 - mb) ** 6)
    return schlick(mu) - b * mu * (1 - mu) ** 6


def test_f82_fit_recovers_an_f82_tint_term():
    r = run_fit("f82-tint:f0=0.8,tint=0.9")
    assert np.allclose(r["f0"], 0.8, atol=1e-12) and np.allclose(r["tint"], 0.9, atol=1e-12)
    assert max(r["max_error"]) < 1e-12


@pytest.mark.parametrize("metal", ["Au", "Cu"])
def test_f82_fit_of_metals_matches_numpy(metal):
    files = {"Au": "Au-Johnson.yml", "Cu": "Cu-Johnson.yml"}
    nk = read_nk(files[metal])
    nm, w = colour_weights()
    n = np.interp(nm * 1e-3, nk[:, 0], nk[:, 1]) + 1j * np.interp(nm * 1e-3, nk[:, 0], nk[:, 2])
    thetas = np.linspace(0, 90, 361)
    mus = np.sin(np.radians(90 - thetas))
    rgb = np.array([IEC_SRGB @ (w @ fresnel_exact(m, n)) for m in mus])
    mb = 1.0 / 7.0
    rgb_mb = IEC_SRGB @ (w @ fresnel_exact(mb, n))
    r = run_fit("metal:" + metal)
    for c in range(3):
        f0 = rgb[0, c]
        tint = rgb_mb[c] / (f0 + (1 - f0) * (1 - mb) ** 5)
        err = np.max(np.abs(f82_tint(mus, f0, tint) - rgb[:, c]))
        assert abs(r["f0"][c] - f0) < 2e-3 and abs(r["tint"][c] - tint) < 3e-3, (metal, c, r, f0, tint)
        assert abs(r["max_error"][c] - err) < 3e-3, (metal, c, r["max_error"][c], err)


# ------------------------------------------------------------ pictures: fresnel --rgb --swatch

def read_png_rgb(path):
    """An 8-bit RGB PNG's pixels (rows, columns, 3) by zlib and the five PNG filters (PNG spec,
    ISO/IEC 15948 sec. 9), without an imaging library."""
    import struct
    import zlib
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour == 2, (depth, colour)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = 3 * width
    out = np.zeros((height, stride), dtype=np.int64)
    prev = np.zeros(stride, dtype=np.int64)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=y * (stride + 1) + 1).astype(np.int64)
        cur = np.zeros(stride, dtype=np.int64)
        for x in range(stride):
            a = cur[x - 3] if x >= 3 else 0
            b = prev[x]
            c = prev[x - 3] if x >= 3 else 0
            if f == 0:
                p = 0
            elif f == 1:
                p = a
            elif f == 2:
                p = b
            elif f == 3:
                p = (a + b) // 2
            else:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                p = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
            cur[x] = (line[x] + p) & 255
        out[y] = cur
        prev = cur
    return out.reshape(height, width, 3)


def srgb_8bit(linear):
    """IEC 61966-2-1:1999 sec. 5.2 encoding, clipped to [0, 1], as 8-bit levels."""
    v = np.clip(linear, 0.0, 1.0)
    e = np.where(v <= 0.0031308, 12.92 * v, 1.055 * v ** (1 / 2.4) - 0.055)
    return np.rint(255 * e).astype(int)


def block_corners(pixels, colour, size):
    """The (row, column) corners of every size x size block of pixels within one level of `colour`
    in every channel."""
    ok = np.all(np.abs(pixels - np.array(colour)) <= 1, axis=2).astype(np.int64)
    s = np.pad(ok.cumsum(0).cumsum(1), ((1, 0), (1, 0)))
    box = s[size:, size:] - s[:-size, size:] - s[size:, :-size] + s[:-size, :-size]
    return np.argwhere(box == size * size)


def has_block(pixels, colour, size):
    """Whether some size x size block of pixels lies within one level of `colour` in every channel."""
    return len(block_corners(pixels, colour, size)) > 0


def test_metal_swatches_hold_the_srgb_encoded_colour(tmp_path):
    """Each swatch's pixels are the numpy colour (CIE tables, n, k of data/nk, exact Fresnel)
    encoded as sRGB, within one 8-bit level (the standard's 4-decimal matrix, and rounding)."""
    path = str(tmp_path / "metals.png")
    thetas = [0, 60, 85]
    out = subprocess.run([EXE, "fresnel", "--rgb", "--fresnel", "metal:Au", "--fresnel", "metal:Cu", "--theta",
                          ",".join(str(t) for t in thetas), "--precision", "double", "--swatch", path],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    pixels = read_png_rgb(path)
    nm, w = colour_weights()
    centres = {}
    for metal, name in (("Au", "Au-Johnson.yml"), ("Cu", "Cu-Johnson.yml")):
        nk = read_nk(name)
        n = np.interp(nm * 1e-3, nk[:, 0], nk[:, 1]) + 1j * np.interp(nm * 1e-3, nk[:, 0], nk[:, 2])
        for theta in thetas:
            colour = srgb_8bit(IEC_SRGB @ (w @ fresnel_exact(np.cos(np.radians(theta)), n)))
            corners = block_corners(pixels, colour, 40)
            assert len(corners) > 0, (metal, theta, colour)
            centres[metal, theta] = corners.mean(axis=0)
    # A colour no swatch has is found nowhere: the check can fail.
    assert not has_block(pixels, (40, 200, 40), 40)
    # The layout: a row per --fresnel in the order given, each the height of the picture over the
    # rows (less the caption's strip), its swatches left to right in --theta's order.
    height, width = pixels.shape[:2]
    for row, metal in enumerate(("Au", "Cu")):
        ys = [centres[metal, t][0] for t in thetas]
        xs = [centres[metal, t][1] for t in thetas]
        assert all(row * height / 2 <= y < (row + 1) * height / 2 for y in ys), (metal, ys, height)
        assert max(ys) - min(ys) < 2, (metal, ys)  # one row
        assert all(a < b for a, b in zip(xs, xs[1:])), (metal, xs)
        for i, x in enumerate(xs):  # swatch i of n in the i-th n-th of the width
            assert i * width / len(thetas) <= x < (i + 1) * width / len(thetas), (metal, i, x, width)


def airy_film(cos_i, lam_nm, d_nm, n1, n2):
    """Reflectance of one film (index n1, thickness d) on a substrate n2 from air: the Airy sum
    r = (r01 + r12 e^{2i delta}) / (1 + r01 r12 e^{2i delta}), delta = 2 pi n1 d cos_1 / lambda
    (Born & Wolf 1.6.4), per polarisation, averaged."""
    sin2 = 1.0 - cos_i ** 2
    c1 = np.sqrt(1.0 - sin2 / n1 ** 2 + 0j)
    c2 = np.sqrt(1.0 - sin2 / n2 ** 2 + 0j)
    delta = 2 * np.pi * n1 * d_nm * c1 / lam_nm
    e = np.exp(2j * delta)
    total = 0.0
    for pol in ("s", "p"):
        if pol == "s":
            r01 = (cos_i - n1 * c1) / (cos_i + n1 * c1)
            r12 = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2)
        else:
            r01 = (n1 * cos_i - c1) / (n1 * cos_i + c1)
            r12 = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2)
        total = total + 0.5 * abs((r01 + r12 * e) / (1 + r01 * r12 * e)) ** 2
    return total


def test_iridescence_map_holds_the_film_colour(tmp_path):
    """The map's cell at theta and thickness d is the numpy Airy colour encoded as sRGB."""
    path = str(tmp_path / "film.png")
    out = subprocess.run([EXE, "fresnel", "--rgb", "--fresnel", "thin-film:eta=1.3,base_eta=1.5", "--thickness-range",
                          "0,1000", "--precision", "double", "--swatch", path, "--format", "json"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    info = json.loads(out.stdout)
    assert info["thickness_nm"] == [0, 1000, 121]
    pixels = read_png_rgb(path)
    nm, w = colour_weights()
    for theta, row in ((30, 60), (0, 36), (60, 90)):
        d = 1000.0 * row / 120
        colour = srgb_8bit(IEC_SRGB @ (w @ airy_film(np.cos(np.radians(theta)), nm, d, 1.3, 1.5)))
        assert has_block(pixels, colour, 3), (theta, d, colour)


def test_iridescence_map_rows_follow_the_thickness_step(tmp_path):
    """--thickness-step NM: ceil((HI - LO) / NM) + 1 rows from LO to HI, evenly spaced (the scene
    setting's rule, docs/fresnel.md); a row at a thickness the default 121 rows lack is the numpy
    Airy colour."""
    nm, w = colour_weights()
    for step, rows, d in ((50, 21, 350.0), (300, 5, 250.0)):
        path = str(tmp_path / "film.png")
        out = subprocess.run([EXE, "fresnel", "--rgb", "--fresnel", "thin-film:eta=1.3,base_eta=1.5",
                              "--thickness-range", "0,1000", "--thickness-step", str(step), "--precision", "double",
                              "--swatch", path, "--format", "json"], capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        assert json.loads(out.stdout)["thickness_nm"] == [0, 1000, rows]
        pixels = read_png_rgb(path)
        colour = srgb_8bit(IEC_SRGB @ (w @ airy_film(np.cos(np.radians(30)), nm, d, 1.3, 1.5)))
        assert has_block(pixels, colour, 3), (step, d, colour)


def test_thin_film_table_slices_follow_the_thickness_step(tmp_path):
    """`lut thin-film --thickness-step NM`: ceil((HI - LO) / NM) + 1 slices over the range, at most
    NM apart (counted in the CSV's thickness column), with --size N or WIDTHxHEIGHT (the error
    message's two forms) beside it."""
    for step, lo, hi, size in ((50, 100, 400, "2"), (70, 0, 1000, "2"), (100, 100, 400, "3x2")):
        path = str(tmp_path / "film.csv")
        out = subprocess.run([EXE, "lut", "thin-film", "--model", "ggx", "--fresnel", "thin-film:eta=1.3,base_eta=1.5",
                              "--wavelength", "550", "--samples", "64", "--size", size, "--thickness-range",
                              f"{lo},{hi}", "--thickness-step", str(step), "--no-preview", "-o", path],
                             capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        d = np.unique(np.loadtxt(path, delimiter=",", comments="#", skiprows=0, usecols=2, dtype=str)[1:].astype(float))
        assert len(d) == int(np.ceil((hi - lo) / step)) + 1, (step, d)
        assert lo <= d[0] and d[-1] <= hi and np.all(np.diff(d) <= step + 1e-9), (step, d)
        mus = np.unique(np.loadtxt(path, delimiter=",", comments="#", usecols=0, dtype=str)[1:].astype(float))
        assert len(mus) == int(size.split("x")[0]), (size, mus)


def test_several_fresnel_terms_in_json_and_csv():
    """Several --fresnel with --rgb: JSON is an array of one object per term, in order; CSV a row
    per term and angle, the term in a first column (RFC 4180 quoting of a spec with commas); each
    colour the numpy one (gold's n, k; the film's Airy sum)."""
    film = "thin-film:eta=1.3,thickness=300,base_eta=1.5"
    thetas = [0, 60]
    nm, w = colour_weights()
    nk = read_nk("Au-Johnson.yml")
    n = np.interp(nm * 1e-3, nk[:, 0], nk[:, 1]) + 1j * np.interp(nm * 1e-3, nk[:, 0], nk[:, 2])
    expect = {"metal:Au": [IEC_SRGB @ (w @ fresnel_exact(np.cos(np.radians(t)), n)) for t in thetas],
              film: [IEC_SRGB @ (w @ airy_film(np.cos(np.radians(t)), nm, 300.0, 1.3, 1.5)) for t in thetas]}
    base = [EXE, "fresnel", "--rgb", "--fresnel", "metal:Au", "--fresnel", film, "--precision", "double", "--theta", "0,60"]
    out = subprocess.run(base + ["--format", "json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    j = json.loads(out.stdout)
    assert isinstance(j, list) and [o["fresnel"] for o in j] == ["metal:Au", film]
    for o in j:
        assert [r["theta_deg"] for r in o["results"]] == thetas
        for r, rgb in zip(o["results"], expect[o["fresnel"]]):
            assert np.all(np.abs(np.array(r["rgb"]) - rgb) <= 2e-3 + np.array(r["rgb_error"])), (o["fresnel"], r, rgb)
    out = subprocess.run(base + ["--format", "csv"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    import csv
    import io
    rows = list(csv.reader(io.StringIO(out.stdout)))
    assert rows[0] == ["fresnel", "theta_deg", "cos_theta", "R", "G", "B", "error_R", "error_G", "error_B"]
    assert [r[0] for r in rows[1:]] == ["metal:Au"] * 2 + [film] * 2
    for r in rows[1:]:
        rgb = expect[r[0]][thetas.index(float(r[1]))]
        assert np.all(np.abs(np.array(r[3:6], dtype=float) - rgb) <= 2e-3 + np.array(r[6:9], dtype=float)), (r, rgb)


def test_swatch_refusals(tmp_path):
    for args, word in ((["--fresnel", "metal:Au", "--swatch", str(tmp_path / "a.png")], "--rgb"),
                       (["--rgb", "--fresnel", "metal:Au", "--swatch", str(tmp_path / "a.txt")], "--swatch"),
                       (["--rgb", "--fresnel", "metal:Au", "--thickness-range", "0,100", "--swatch",
                         str(tmp_path / "a.png")], "thin-film"),
                       (["--fresnel", "metal:Au", "--fresnel", "metal:Cu"], "--rgb"),
                       (["--rgb", "--fresnel", "thin-film:eta=1.3,base_eta=1.5", "--thickness-step", "20"],
                        "--thickness-range"),
                       (["--rgb", "--fresnel", "thin-film:eta=1.3,base_eta=1.5", "--thickness-range", "0,100",
                         "--thickness-step", "0", "--swatch", str(tmp_path / "a.png")], "--thickness-step"),
                       (["--rgb", "--fresnel", "thin-film:eta=1.3,base_eta=1.5", "--thickness-range", "0,100",
                         "--thickness-step", "150", "--swatch", str(tmp_path / "a.png")], "--thickness-step"),
                       (["--rgb", "--fresnel", "thin-film:eta=1.3,base_eta=1.5", "--thickness-range", "0,1000",
                         "--thickness-step", "0.5", "--swatch", str(tmp_path / "a.png")], "--thickness-step")):
        out = subprocess.run([EXE, "fresnel"] + args, capture_output=True, text=True)
        assert out.returncode == 2 and out.stderr.startswith("brdfbake: error:") and word in out.stderr, (args, out.stderr)
        assert not os.path.exists(str(tmp_path / "a.png"))
    for args, word in ((["albedo", "--model", "ggx", "--thickness-step", "20"], "thin-film"),
                       (["thin-film", "--model", "ggx", "--fresnel", "thin-film:eta=1.3,base_eta=1.5",
                         "--thickness-step", "-5"], "--thickness-step"),
                       (["thin-film", "--model", "ggx", "--fresnel", "thin-film:eta=1.3,base_eta=1.5",
                         "--thickness-step", "20", "--size", "8x8x4"], "--thickness-step"),
                       (["thin-film", "--model", "ggx", "--fresnel", "thin-film:eta=1.3,base_eta=1.5",
                         "--thickness-step", "1"], "256")):
        out = subprocess.run([EXE, "lut"] + args + ["--no-preview", "-o", str(tmp_path / "t.csv")],
                             capture_output=True, text=True)
        assert out.returncode == 2 and out.stderr.startswith("brdfbake: error:") and word in out.stderr, (args, out.stderr)
        assert out.stderr.count("\n") == 1 and not os.path.exists(str(tmp_path / "t.csv"))
