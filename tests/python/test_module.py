"""The Python module against truths from outside it: closed forms, a numpy quadrature of the
textbook formulas, the command line's own files and messages, and the README's example.

Run by CTest (`ctest -R python`) with the interpreter the module was built for and
PYTHONPATH pointing at the build's python/ folder."""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
import pytest

import brdfbake

EXE = os.environ.get("BRDFBAKE_EXE", "brdfbake")
SOURCE_DIR = os.environ.get(
    "BRDFBAKE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def run_cli(*args):
    return subprocess.run([EXE, *args], capture_output=True, text=True)


def as_python(message):
    """The command line's message as the module words it: a flag is the argument of the same
    name (--mu-map is mu_map)."""
    return re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_"), message)


# ------------------------------------------------------------------ independent references

def ggx_f(wo, wi, alpha):
    """Textbook GGX with the height-correlated Smith term (Heitz 2014, eq. 99), F = 1, in
    numpy; wo, wi of shape (..., 3), normal +z."""
    h = wo + wi
    h = h / np.linalg.norm(h, axis=-1, keepdims=True)
    a2 = alpha * alpha
    cos_h2 = h[..., 2] ** 2
    d = a2 / (np.pi * (cos_h2 * (a2 - 1.0) + 1.0) ** 2)

    def lam(w):
        c2 = w[..., 2] ** 2
        t2 = (1.0 - c2) / c2
        return 0.5 * (-1.0 + np.sqrt(1.0 + a2 * t2))

    g2 = 1.0 / (1.0 + lam(wo) + lam(wi))
    return d * g2 / (4.0 * wo[..., 2] * wi[..., 2])


def ggx_albedo_quadrature(alpha, mu_o, n=600):
    """E(mu_o) = int f cos(theta_i) dwi by Gauss-Legendre in (cos theta_i, phi_i), mirror
    symmetric in phi: an independent reference (about 1e-9 at alpha = 0.5)."""
    x, w = np.polynomial.legendre.leggauss(n)
    mu_i = 0.5 * (x + 1.0)
    wmu = 0.5 * w
    phi = 0.5 * np.pi * (x + 1.0)
    wphi = 0.5 * np.pi * w
    M, P = np.meshgrid(mu_i, phi, indexing="ij")
    s = np.sqrt(1.0 - M * M)
    wi = np.stack([s * np.cos(P), s * np.sin(P), M], axis=-1)
    so = np.sqrt(1.0 - mu_o * mu_o)
    wo = np.broadcast_to(np.array([so, 0.0, mu_o]), wi.shape)
    f = ggx_f(wo, wi, alpha)
    return 2.0 * np.sum(f * M * np.outer(wmu, wphi))


# ------------------------------------------------------------------ albedo

def test_lambert_albedo_is_rho():
    mu = np.linspace(0.05, 1.0, 7)
    r = brdfbake.albedo("lambert:rho=0.8", mu)
    assert r.albedo.shape == mu.shape and r.albedo.dtype == np.float64
    assert r.error.shape == mu.shape and r.error.dtype == np.float64
    assert np.all(np.abs(r.albedo - 0.8) <= 1e-6)
    assert r.model == "lambert:rho=0.8"
    assert r.samples > 0 and r.seconds > 0 and r.device


def test_ggx_albedo_against_numpy_quadrature():
    truth = ggx_albedo_quadrature(0.5, 0.5)
    for kwargs in ({}, {"tolerance": 1e-6, "precision": "double"}):
        r = brdfbake.albedo("ggx:alpha=0.5", 0.5, **kwargs)
        assert r.albedo.shape == ()
        got, err = float(r.albedo), float(r.error)
        assert abs(got - truth) <= err, (kwargs, got, err, truth)
        assert err <= 1e-4


def test_albedo_keeps_the_shape_of_mu_and_broadcasts_phi():
    mu = np.array([[0.25, 0.5, 1.0], [0.1, 0.2, 0.3]])
    r = brdfbake.albedo("ggx:alpha_x=0.2,alpha_y=0.6", mu, phi=30.0, samples=4096)
    assert r.albedo.shape == (2, 3) and r.error.shape == (2, 3)
    # phi is reduced exactly: 30 and 390 degrees are one direction.
    again = brdfbake.albedo("ggx:alpha_x=0.2,alpha_y=0.6", mu, phi=390.0, samples=4096)
    assert np.array_equal(r.albedo, again.albedo)


# ------------------------------------------------------------------ tables

def read_cli_csv(path):
    header, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                continue
            if header is None:
                header = line.strip().split(",")
                continue
            rows.append([float(v) for v in line.strip().split(",")])
    return header, np.array(rows)


def test_lut_equals_the_command_line_table():
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "t.csv")
        cli = run_cli("lut", "dfg", "--model", "ggx", "--size", "8x4", "--samples", "4096", "-o", path,
                      "--no-preview")
        assert cli.returncode == 0, cli.stderr
        header, rows = read_cli_csv(path)
        t = brdfbake.lut("dfg", "ggx", size=(8, 4), samples=4096)
        assert t.values.shape == (4, 8, len(t.channels)) and t.values.dtype == np.float64
        assert t.error.shape == (4, 8)
        assert [a["name"] for a in t.axes] == header[:2]
        # Rows are texels, x fastest, as numpy's C order of values[y, x].
        for c, name in enumerate(t.channels):
            col = rows[:, header.index(name)]
            np.testing.assert_allclose(t.values[..., c].ravel(), col, rtol=6e-9, atol=0)
        np.testing.assert_allclose(t.error.ravel(), rows[:, header.index("error")], rtol=6e-4, atol=0)
        assert t.attributes["model"] == "ggx:shadowing=correlated"
        np.testing.assert_allclose(t.axes[0]["coordinate"], (np.arange(8) + 0.5) / 8)


def test_lut_shapes_of_1d_and_3d_tables():
    e = brdfbake.lut("eavg", "ggx", size=6, samples=1024)
    assert e.values.shape == (6, 1) and e.error.shape == (6,)
    d = brdfbake.lut("dielectric", "ggx", size=(4, 3, 2), samples=1024)
    assert d.values.shape == (2, 3, 4, len(d.channels)) and len(d.axes) == 3


def test_save_writes_what_the_command_line_reads_back():
    t = brdfbake.lut("albedo", "ggx", size=(4, 4), samples=1024)
    with tempfile.TemporaryDirectory() as d:
        for ext in ("exr", "csv", "h"):
            path = os.path.join(d, "t." + ext)
            t.save(path)
            assert os.path.getsize(path) > 0
        header, rows = read_cli_csv(os.path.join(d, "t.csv"))
        np.testing.assert_allclose(rows[:, header.index("E")], t.values[..., 0].ravel(), rtol=6e-9)


# ------------------------------------------------------------------ fresnel, eval, check

def test_fresnel_of_a_dielectric_is_the_textbook_formula():
    theta = np.array([0.0, 30.0, 60.0, 89.0])
    r = brdfbake.fresnel("dielectric:eta=1.5", theta, precision="double")
    c = np.cos(np.radians(theta))
    s = np.sqrt(1.5 ** 2 - 1.0 + c * c)
    rs = ((c - s) / (c + s)) ** 2
    rp = ((1.5 ** 2 * c - s) / (1.5 ** 2 * c + s)) ** 2
    np.testing.assert_allclose(r["Rs"], rs, atol=1e-12)
    np.testing.assert_allclose(r["Rp"], rp, atol=1e-12)
    np.testing.assert_allclose(r["F"], 0.5 * (rs + rp), atol=1e-12)


def test_eval_agrees_with_the_textbook_formula():
    rng = np.random.default_rng(7)

    def unit_upper(n):
        v = rng.normal(size=(n, 3))
        v[:, 2] = np.abs(v[:, 2]) + 0.05
        return v / np.linalg.norm(v, axis=1, keepdims=True)

    wo, wi = unit_upper(64), unit_upper(64)
    f = brdfbake.eval("ggx:alpha=0.3", wo, wi)
    assert f.shape == (64,) and f.dtype == np.float64
    np.testing.assert_allclose(f, ggx_f(wo, wi, 0.3), rtol=1e-10)
    lam = brdfbake.eval("lambert:rho=0.5", wo.reshape(8, 8, 3), wi.reshape(8, 8, 3))
    assert lam.shape == (8, 8)
    np.testing.assert_allclose(lam, 0.5 / np.pi, rtol=1e-14)



def test_diffuse_adds_a_lambert_base_of_kd_over_pi():
    """diffuse=KD on a Smith lobe (ggx, beckmann): f is the lobe plus kd/pi (a closed form), for
    GGX the numpy textbook formula plus kd/pi; the albedo the numpy quadrature of the lobe plus kd."""
    rng = np.random.default_rng(11)
    v = rng.normal(size=(2, 48, 3))
    v[..., 2] = np.abs(v[..., 2]) + 0.05
    wo, wi = v / np.linalg.norm(v, axis=-1, keepdims=True)
    kd = 0.25
    f = brdfbake.eval("ggx:alpha=0.3,diffuse=0.25", wo, wi)
    np.testing.assert_allclose(f, ggx_f(wo, wi, 0.3) + kd / np.pi, rtol=1e-10)
    lobe = brdfbake.eval("beckmann:alpha=0.4", wo, wi)
    both = brdfbake.eval("beckmann:alpha=0.4,diffuse=0.25", wo, wi)
    np.testing.assert_allclose(both - lobe, kd / np.pi, rtol=1e-10, atol=1e-14)
    r = brdfbake.albedo("ggx:alpha=0.5,diffuse=0.25", 0.5)
    truth = ggx_albedo_quadrature(0.5, 0.5) + kd
    assert abs(float(r.albedo) - truth) <= float(r.error), (float(r.albedo), float(r.error), truth)
    assert float(r.error) <= 1e-4

def test_a_simulated_layer_is_refused_where_f_is_pointwise_and_tabled_by_lut():
    """sheen-volume (a random walk) has no pointwise f: eval and albedo refuse it with one line saying
    so; lut albedo tables it, R + T of a non-absorbing layer with nothing cut off at most 1 (R in [0, 1])."""
    w = np.array([[0.0, 0.0, 1.0]])
    for call in (lambda: brdfbake.eval("sheen-volume:roughness=0.5", w, w),
                 lambda: brdfbake.albedo("sheen-volume:roughness=0.5", 0.5)):
        with pytest.raises(ValueError, match="no pointwise value.*this command does not"):
            call()
    t = brdfbake.lut("albedo", model="sheen-volume", alpha_map="roughness", size=(2, 2), samples=4096)
    r, err = np.asarray(t.values)[..., 0], np.asarray(t.error)
    assert t.channels == ["E"] and r.shape == err.shape == (2, 2)
    assert np.all(np.isfinite(r)) and np.all(np.isfinite(err)) and np.all(err > 0)
    assert np.all(r >= -err) and np.all(r <= 1 + err)


def test_check_gives_the_verdict():
    ok = brdfbake.check("ggx:alpha=0.5", directions=4, samples=4096, resolution=8)
    assert ok["passed"] is True and ok["energy"]["violation"] is False
    assert ok["energy"]["max_albedo"] <= 1.0 + ok["energy"]["error"]
    # phong-original divides by cos(theta_i): not reciprocal, and the check says so.
    bad = brdfbake.check("phong-original:n=10", directions=4, samples=4096, resolution=8)
    assert bad["passed"] is False and bad["reciprocity"]["violation"] is True


# ------------------------------------------------------------------ errors

@pytest.mark.parametrize("spec", ["ggx:alpha=-1", "blinn-phongg:n=10", "ggx", "ggx:alpha=0.5,beta=2"])
def test_bad_specs_raise_value_error_with_the_command_lines_message(spec):
    cli = run_cli("albedo", "--model", spec, "--mu", "0.5")
    assert cli.returncode == 2
    message = cli.stderr.strip()
    assert message.startswith("brdfbake: error: ")
    with pytest.raises(ValueError) as e:
        brdfbake.albedo(spec, 0.5)
    assert str(e.value) == as_python(message[len("brdfbake: error: "):])


def test_other_bad_input_raises_value_error():
    with pytest.raises(ValueError, match="mu"):
        brdfbake.albedo("lambert", 1.5)
    with pytest.raises(ValueError, match="precision"):
        brdfbake.albedo("lambert", 0.5, precision="half")
    with pytest.raises(ValueError, match="unknown table kind|kind"):
        brdfbake.lut("nonsense", "ggx", size=4)
    with pytest.raises(ValueError, match="last axis of 3"):
        brdfbake.eval("lambert", np.zeros((4, 2)), np.zeros((4, 2)))


def test_errors_name_the_python_arguments_not_the_flags():
    with pytest.raises(ValueError) as e:
        brdfbake.albedo("lambert", 1.5)
    assert str(e.value) == "mu: 1.5 is out of range; mu = cos(theta_o) must lie in (0, 1]"
    with pytest.raises(ValueError) as e:
        brdfbake.albedo("lambert", 0.5, tolerance=-1.0)
    assert "tolerance" in str(e.value) and "--" not in str(e.value)
    with pytest.raises(ValueError) as e:
        brdfbake.lut("dielectric", "ggx", size=(4, 4))
    assert str(e.value) == ("size: a dielectric table has 3 axes (mu x alpha x eta); give N (the same on every "
                            "axis) or WIDTHxHEIGHTxDEPTH (size 4x4)")
    with pytest.raises(ValueError) as e:
        brdfbake.lut("albedo", "ggx", size=4, mu_map="cube")
    assert "mu_map" in str(e.value) and "--" not in str(e.value)


def test_lut_refuses_an_output_format_that_cannot_hold_the_table_before_the_compute():
    # three.js's DataTexture holds 1, 2 or 4 channels; the ltc table in three's packing has 10.
    # The whole 64 x 64 fit took 11 s of CPU before this refusal came (lut_table_shape).
    import time
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "ltc.js")
        t0 = time.monotonic()
        with pytest.raises(ValueError) as e:
            brdfbake.lut("ltc", preset="three", output=path)
        assert time.monotonic() - t0 < 1.0
        assert str(e.value).startswith("a three.js half-float DataTexture has 1, 2 or 4 channels")
        assert "\n" not in str(e.value)
        assert os.listdir(d) == []


def test_a_mistyped_keyword_gets_one_line_with_the_nearest_argument():
    with pytest.raises(TypeError) as e:
        brdfbake.albedo("lambert", 0.5, tolerence=1e-3)
    assert str(e.value) == "albedo() got an unexpected keyword argument 'tolerence'; did you mean 'tolerance'?"
    with pytest.raises(TypeError) as e:
        brdfbake.lut("albedo", "ggx", sizes=4)
    assert str(e.value) == "lut() got an unexpected keyword argument 'sizes'; did you mean 'size'?"
    with pytest.raises(TypeError) as e:
        brdfbake.albedo("lambert", 0.5, frobnicate=1)
    assert str(e.value) == ("albedo() got an unexpected keyword argument 'frobnicate'; its arguments: model, mu, phi, "
                            "fresnel, wavelength, samples, tolerance, method, max_samples, precision, device")
    with pytest.raises(TypeError) as e:
        brdfbake.albedo("lambert")
    assert str(e.value) == "albedo() missing required argument 'mu'"
    with pytest.raises(TypeError) as e:
        brdfbake.albedo("lambert", 0.5, model="ggx")
    assert str(e.value) == "albedo() got multiple values for argument 'model'"
    # help() still shows the arguments
    assert "albedo(model: str, mu: " in brdfbake.albedo.__doc__


def test_strings_for_numbers_are_refused():
    with pytest.raises(TypeError) as e:
        brdfbake.albedo("lambert", "0.5")
    assert str(e.value) == "albedo(): mu must be a number or an array of numbers, not the string '0.5'"
    with pytest.raises(TypeError) as e:
        brdfbake.albedo("lambert", ["0.5", "1"])
    assert str(e.value) == "albedo(): mu must be numbers, not an array of <U3"
    with pytest.raises(TypeError) as e:
        brdfbake.albedo("lambert", 0.5, samples="1024")
    assert str(e.value) == "albedo(): samples must be a number, not the string '1024'"
    with pytest.raises(TypeError) as e:
        brdfbake.fresnel("schlick:f0=0.04", theta_deg="45")
    assert str(e.value) == "fresnel(): theta_deg must be a number or an array of numbers, not the string '45'"
    # numbers in every spelling still pass: int, float, numpy scalars, lists, arrays
    for mu in (1, 0.5, np.float32(0.5), [0.5, 1], np.array([0.25, 0.5])):
        r = brdfbake.albedo("lambert:rho=0.5", mu, samples=64)
        assert np.allclose(r.albedo, 0.5, atol=1e-6)


def test_the_registries_are_the_command_lines():
    assert "ggx" in brdfbake.models() and "lambert" in brdfbake.models()
    assert "albedo" in brdfbake.table_kinds() and "dfg" in brdfbake.table_kinds()
    assert "schlick" in brdfbake.fresnel_terms() and "metal" in brdfbake.fresnel_terms()


# ------------------------------------------------------------------ the README's example

def test_readme_example_runs_as_written():
    with open(os.path.join(SOURCE_DIR, "README.md")) as f:
        readme = f.read()
    blocks = re.findall(r"<!-- python-example -->\s*```python\n(.*?)```", readme, re.S)
    assert blocks, "the README has no <!-- python-example --> block"
    with tempfile.TemporaryDirectory() as d:
        script = os.path.join(d, "example.py")
        with open(script, "w") as f:
            f.write(blocks[0])
        r = subprocess.run([sys.executable, script], cwd=d, capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        assert os.path.exists(os.path.join(d, "dfg.exr"))


def test_ctrl_c_raises_keyboard_interrupt_at_the_next_kernel_launch():
    # A tolerance no method reaches soon: many refinement rounds, each a kernel launch.
    script = (
        "import signal, sys, brdfbake\n"
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"  # a background job may inherit SIG_IGN
        "print('started', flush=True)\n"
        "try:\n"
        "    brdfbake.lut('albedo', 'beckmann', size=(64, 64), tolerance=1e-7, precision='double',\n"
        "                 method='importance', max_samples=2**30)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
        "    sys.exit(3)\n"
    )
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "started"
    import signal
    import time
    time.sleep(2.0)
    p.send_signal(signal.SIGINT)
    try:
        out, _ = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        p.kill()
        raise AssertionError("Ctrl-C did not stop the computation")
    assert p.returncode == 3 and "interrupted" in out


# ------------------------------------------------------------------ read_table, presets

@pytest.mark.parametrize("kind,size,extra", [
    ("dfg", (6, 4), {}),
    ("eavg", 5, {}),
    ("dielectric", (4, 3, 2), {}),
    ("albedo", (5, 3), {"alpha_map": "roughness", "texels": "edge", "flip": ["mu"]}),
])
def test_read_table_round_trips_every_format(kind, size, extra):
    t = brdfbake.lut(kind, "ggx", size=size, samples=1024, **extra)
    with tempfile.TemporaryDirectory() as d:
        for ext, rtol_value, rtol_error in (("npy", 0, 0), ("exr", None, None), ("csv", 6e-9, 6e-4)):
            path = os.path.join(d, "t." + ext)
            t.save(path)
            back = brdfbake.read_table(path)
            assert (back.kind, back.quantity, back.channels) == (t.kind, t.quantity, t.channels)
            assert back.attributes == t.attributes
            assert back.values.shape == t.values.shape and back.error.shape == t.error.shape
            for a, b in zip(t.axes, back.axes):
                assert (a["name"], a["mapping"], a["size"], a["texels"]) == (b["name"], b["mapping"], b["size"], b["texels"])
                np.testing.assert_allclose(b["coordinate"], a["coordinate"], rtol=1e-15, atol=1e-15)
            if ext == "exr":  # float32 samples: exactly the table's values rounded to float
                assert np.array_equal(back.values, t.values.astype(np.float32).astype(np.float64))
                assert np.array_equal(back.error, t.error.astype(np.float32).astype(np.float64))
            else:
                np.testing.assert_allclose(back.values, t.values, rtol=rtol_value, atol=0)
                np.testing.assert_allclose(back.error, t.error, rtol=rtol_error, atol=0)
            # The per-texel parameters (alpha of a roughness axis) come back from every format.
            for a, b in zip(t.axes, back.axes):
                np.testing.assert_allclose(b["parameter"], a["parameter"], rtol=6e-9)


def test_read_table_refuses_what_is_not_a_table():
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "x.csv")
        with open(path, "w") as f:
            f.write("a,b\n1,2\n")
        with pytest.raises(ValueError, match="not a brdfbake table"):
            brdfbake.read_table(path)
        with pytest.raises(ValueError, match="reads back"):
            brdfbake.read_table(os.path.join(d, "x.txt"))


def test_a_preset_equals_the_command_lines():
    assert "cycles" in brdfbake.presets()
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "e.npy")
        cli = run_cli("lut", "--preset", "cycles", "-o", path, "--no-preview")
        assert cli.returncode == 0, cli.stderr
        from_cli = brdfbake.read_table(path)
        t = brdfbake.lut(preset="cycles")
        assert t.kind == from_cli.kind and t.attributes == from_cli.attributes
        assert np.array_equal(t.values, from_cli.values)


# ------------------------------------------------------------------ lut() has every option of `brdfbake lut`

def cli_lut_options():
    """The options `brdfbake lut --help` lists, by their long names."""
    cli = run_cli("lut", "--help")
    assert cli.returncode == 0, cli.stderr
    names = set(re.findall(r"^\s+(?:-\w,)?(--[a-z][a-z0-9-]*)", cli.stdout, re.M))
    assert {"--preset", "--model", "--size"} <= names, cli.stdout
    return sorted(names)


# The options that are not about the table: where the module has them instead, or why not.
NOT_LUT_ARGUMENTS = {
    "--help": "Python's help(brdfbake.lut)",
    "--preview": "the command line's preview picture (drawn with MathGL, which the module does not link)",
    "--no-preview": "the module draws no preview",
    "--shard": "part files for `brdfbake merge`; a Python call computes the whole table",
}

# Every lut option with a value for it: (command-line words, lut() keyword arguments). Each is
# given on top of a small albedo table of ggx; lut() must then write what the command line
# writes, or refuse it with the command line's message.
LUT_OPTION_VALUES = {
    "--preset": (["--preset", "cycles"], {"preset": "cycles"}),
    "--model": (["--model", "ggx:shadowing=separable"], {"model": "ggx:shadowing=separable"}),
    "--estimator": (["--estimator", "cycles"], {"estimator": "cycles"}),
    "--fresnel": (["--fresnel", "schlick:f0=0.5"], {"fresnel": "schlick:f0=0.5"}),
    "--wavelength": (["--fresnel", "metal:Au", "--wavelength", "600"], {"fresnel": "metal:Au", "wavelength": 600.0}),
    "--size": (["--size", "3x2"], {"size": (3, 2)}),
    "--mu-map": (["--mu-map", "sqrt"], {"mu_map": "sqrt"}),
    "--alpha-map": (["--alpha-map", "roughness"], {"alpha_map": "roughness"}),
    "--alpha-range": (["--alpha-range", "0.1,0.9"], {"alpha_range": [0.1, 0.9]}),
    "--eta-range": (["--eta-range", "1.2,2"], {"eta_range": [1.2, 2.0]}),
    "--thickness-range": (["--thickness-range", "0,300"], {"thickness_range": [0.0, 300.0]}),
    "--thickness-step": (["--thickness-step", "50"], {"thickness_step": 50.0}),
    "--eta-map": (["--eta-map", "f0"], {"eta_map": "f0"}),
    "--texels": (["--texels", "edge"], {"texels": "edge"}),
    "--mu-range": (["--mu-range", "0.2,1"], {"mu_range": [0.2, 1.0]}),
    "--mu-floor": (["--mu-floor", "0.3"], {"mu_floor": 0.3}),
    "--axes": (["--axes", "alpha,mu"], {"axes": ["alpha", "mu"]}),
    "--flip": (["--flip", "mu"], {"flip": ["mu"]}),
    "--samples": (["--samples", "512"], {"samples": 512}),
    "--method": (["--method", "qmc"], {"method": "qmc"}),
    "--tolerance": (["--tolerance", "1e-3"], {"tolerance": 1e-3}),
    "--max-samples": (["--tolerance", "1e-3", "--max-samples", "4096"], {"tolerance": 1e-3, "max_samples": 4096}),
    "--precision": (["--precision", "double"], {"precision": "double"}),
    "--half": (["--half"], {"half": True}),
    "--colour-space": (["--fresnel", "metal:Au", "--colour-space", "acescg"], {"fresnel": "metal:Au", "colour_space": "acescg"}),
    "--rgb-wavelengths": (["--fresnel", "metal:Au", "--rgb-wavelengths"], {"fresnel": "metal:Au", "rgb_wavelengths": True}),
    "--output": ([], {}),  # every call writes its table: -o and output=
}


def lut_both_ways(words, kwargs, d, name):
    """Runs `brdfbake lut albedo --model ggx --size 2x2 --samples 64 WORDS -o FILE` and lut() with
    the same settings; returns (CLI's table or message, Python's)."""
    cli_path, py_path = os.path.join(d, name + "-cli.exr"), os.path.join(d, name + "-py.exr")
    base_words = {"--model": ["ggx"], "--size": ["2x2"], "--samples": ["64"]}
    base_kwargs = {"model": "ggx", "size": (2, 2), "samples": 64}
    for w in words:  # an option given replaces the base's (and --tolerance its --samples)
        base_words.pop(w, None)
        if w == "--tolerance":
            base_words.pop("--samples", None)
    for k in kwargs:
        base_kwargs.pop(k, None)
        if k == "tolerance":
            base_kwargs.pop("samples", None)
    args = ["lut", "albedo"] + [x for k, v in base_words.items() for x in [k] + v] + words
    cli = run_cli(*args, "--no-preview", "-o", cli_path)
    if cli.returncode != 0:
        assert cli.returncode == 2, cli.stderr
        cli_out = as_python(cli.stderr.strip()[len("brdfbake: error: "):])
    else:
        cli_out = brdfbake.read_table(cli_path)
    try:
        brdfbake.lut("albedo", output=py_path, **base_kwargs, **kwargs)
        py_out = brdfbake.read_table(py_path)
    except ValueError as e:
        py_out = str(e)
    return cli_out, py_out


def test_lut_takes_every_option_of_the_command_line():
    options = cli_lut_options()
    missing = [o for o in options if o not in LUT_OPTION_VALUES and o not in NOT_LUT_ARGUMENTS]
    assert not missing, "brdfbake lut options without a lut() argument in this test: " + ", ".join(missing)
    with tempfile.TemporaryDirectory() as d:
        for option in options:
            if option in NOT_LUT_ARGUMENTS:
                continue
            words, kwargs = LUT_OPTION_VALUES[option]
            try:
                cli_out, py_out = lut_both_ways(words, kwargs, d, option.strip("-"))
            except TypeError as e:  # lut() has no such keyword
                raise AssertionError("lut() lacks " + option + ": " + str(e))
            if isinstance(cli_out, str) or isinstance(py_out, str):
                assert cli_out == py_out, option
                continue
            assert py_out.attributes == cli_out.attributes, option
            assert np.array_equal(py_out.values, cli_out.values), option
            assert [a["name"] for a in py_out.axes] == [a["name"] for a in cli_out.axes], option


@pytest.mark.parametrize("words,kwargs", [
    (["--preset", "gltf", "eavg"], {"preset": "gltf", "kind": "eavg"}),
    (["dfg", "--model", "ggx", "--estimator", "cycles"], {"kind": "dfg", "model": "ggx", "estimator": "cycles"}),
    (["--model", "ggx"], {"model": "ggx"}),
    (["albedo"], {"kind": "albedo"}),
    (["albedo", "--model", "ggx", "--size", "2x2x2"], {"kind": "albedo", "model": "ggx", "size": (2, 2, 2)}),
    (["eavg", "--model", "ggx", "--size", "4x4"], {"kind": "eavg", "model": "ggx", "size": (4, 4)}),
    (["albedo", "--model", "ggx", "--alpha-range", "0.1,0.2,0.3"],
     {"kind": "albedo", "model": "ggx", "alpha_range": [0.1, 0.2, 0.3]}),
    (["gen-schlick", "--preset", "cycles", "--estimator", "cycles", "--model", "ggx"],
     {"kind": "gen-schlick", "preset": "cycles", "estimator": "cycles", "model": "ggx"}),
    (["albedo", "--preset", "nope"], {"kind": "albedo", "preset": "nope"}),
])
def test_lut_refuses_what_the_command_line_refuses_with_its_message(words, kwargs):
    with tempfile.TemporaryDirectory() as d:
        cli = run_cli("lut", *words, "--no-preview", "-o", os.path.join(d, "t.exr"))
        assert cli.returncode == 2, cli.stderr
        message = cli.stderr.strip()
        assert message.startswith("brdfbake: error: ")
        with pytest.raises(ValueError) as e:
            brdfbake.lut(**kwargs)
        assert str(e.value) == as_python(message[len("brdfbake: error: "):])
        assert not os.listdir(d)
