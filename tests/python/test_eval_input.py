"""brdfbake.eval's inputs (issue 31): directions that are not finite unit vectors are refused
with ValueError naming the array and index, never evaluated to a number; and an eval too large
for the memory limit is refused before anything is allocated on the device.

Run by CTest (`ctest -R python`) with PYTHONPATH pointing at the build's python/ folder."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import brdfbake

UP = np.array([[0.0, 0.0, 1.0]])


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_directions_raise_value_error(bad):
    wo = np.array([[0.0, bad, 1.0]])
    with pytest.raises(ValueError, match=r"wo\[0\].*not a unit vector"):
        brdfbake.eval("ggx:alpha=0.5", wo, UP)
    with pytest.raises(ValueError, match=r"wi\[0\].*not a unit vector"):
        brdfbake.eval("ggx:alpha=0.5", UP, wo)


def test_non_unit_directions_are_refused_not_evaluated():
    # (0, 0, 5) gave 0.0723 where (0, 0, 1) gives 0.2277: a length that is not 1 is refused.
    for v in ([0.0, 0.0, 5.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.001]):
        with pytest.raises(ValueError, match="length"):
            brdfbake.eval("ggx:alpha=0.5", np.array([v]), UP)
    # The index names the offending pair in a larger array.
    wo = np.repeat(UP, 5, axis=0)
    wo[3] = [0.0, 0.0, 2.0]
    with pytest.raises(ValueError, match=r"wo\[3\]"):
        brdfbake.eval("ggx:alpha=0.5", wo, np.repeat(UP, 5, axis=0))


def test_float32_unit_vectors_are_taken_and_normalised():
    # A unit vector rounded to float32 is within 1e-7 of length 1: taken, and evaluated as the
    # exact unit vector (lambert: rho / pi whatever the directions).
    v = np.array([[0.3, 0.4, math.sqrt(1 - 0.25)]], dtype=np.float32)
    f = brdfbake.eval("lambert:rho=0.5", v, v)
    assert f.shape == (1,)
    assert abs(f[0] - 0.5 / math.pi) < 1e-15


def test_a_huge_eval_is_refused_by_the_memory_check_before_work():
    # 2e6 pairs need the result (16 bytes a pair) and a chunk's device buffers: over a 64 MB
    # limit, refused before the device is touched (2e7 pairs once reached 3.3 GB and then
    # CL_OUT_OF_HOST_MEMORY). In a child process, whose limit is set by its environment.
    code = ("import numpy as np, brdfbake\n"
            "big = np.repeat(np.array([[0.0, 0.0, 1.0]]), 2_000_000, axis=0)\n"
            "try:\n    brdfbake.eval('lambert', big, big)\n"
            "except ValueError as e:\n    print('refused:', e)\n")
    env = dict(os.environ, BRDFBAKE_MAX_MEMORY="64M")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert "refused:" in r.stdout, r.stdout + r.stderr
    assert "memory" in r.stdout and "2000000 direction pairs" in r.stdout
