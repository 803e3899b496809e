"""The Python module with a measured (MERL) model spec: files written by scripts/make_merl.py
(numpy) from known BRDFs, their albedo against closed forms. Run by CTest's `python` test."""
import os
import subprocess
import sys
import tempfile

import numpy as np

import brdfbake

SOURCE_DIR = os.environ.get(
    "BRDFBAKE_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
MAKE_MERL = os.path.join(SOURCE_DIR, "scripts", "make_merl.py")


def test_merl_lambert_file_albedo_is_rho_per_channel():
    """A Lambert file of rho = (0.2, 0.5, 0.8) (every node, below the horizon too): E = rho at
    every mu, for each channel; and Rec. 709 luminance for channel y."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "lambert.binary")
        subprocess.run([sys.executable, MAKE_MERL, "lambert", "--rho", "0.2,0.5,0.8", path], check=True)
        mu = np.array([0.1, 0.5, 1.0])
        for channel, rho in (("r", 0.2), ("g", 0.5), ("b", 0.8),
                             ("y", 0.2126 * 0.2 + 0.7152 * 0.5 + 0.0722 * 0.8)):
            r = brdfbake.albedo("merl:file=%s,channel=%s" % (path, channel), mu)
            assert r.albedo.shape == mu.shape
            assert np.all(np.abs(r.albedo - rho) <= r.error + 1e-9), (channel, r.albedo, r.error)
            assert "merl:file=" in r.model and ("channel=" + channel) in r.model


def test_merl_builtin_lambert_is_one():
    r = brdfbake.albedo("merl:file=builtin:lambert", np.array([0.3, 0.9]))
    assert np.all(np.abs(r.albedo - 1.0) <= r.error + 1e-9)
