#!/usr/bin/python3
"""Two `brdfbake lut ltc --preset three -o FILE.csv` tables (GGX, three.js's grid and packing) by
the independent numpy L1 distance of tests/ltc_reference.py at the same texels (issue 33 item 5:
a faster fitter must not fit worse). Per texel (t, a) of rows t = 0, STEP, 2 STEP, ... and
columns a = 2, 2 + STEP, ...: alpha and mu from the CSV, M from ltc_1 (docs/ltc_presets.md), the
distance at n x n nodes per sampler (error about 5e-5 at n = 128), E computed once for both.

  ltc_table_reference.py BEFORE.csv AFTER.csv [--n 128] [--step 4]

Prints the median and mean of each and the percentiles of AFTER / BEFORE per texel."""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
import ltc_reference as ref  # noqa: E402


def read_three(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    head = rows[0].strip().split(",")
    data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]])
    return {name: data[:, i] for i, name in enumerate(head)}


def matrix(c, k):
    """M from ltc_1 = M^-1 / M^-1_11 as (M^-1_00, M^-1_20, M^-1_02, M^-1_22); D ignores M's scale."""
    r, g, b, a = (c["ltc_1." + ch][k] for ch in "RGBA")
    return np.linalg.inv(ref.matrix_from_channels(r, b, 1.0, g, a))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--n", type=int, default=128)
    ap.add_argument("--step", type=int, default=4)
    o = ap.parse_args()
    x, y = read_three(o.before), read_three(o.after)
    size = int(round(np.sqrt(len(x["mu"]))))
    assert np.array_equal(x["mu"], y["mu"]) and np.array_equal(x["alpha"], y["alpha"])
    dx, dy = [], []
    for t in range(0, size, o.step):
        for a in range(2, size, o.step):
            k = t * size + a  # x = roughness (a), y = sqrt(1 - mu) (t)
            mu, alpha = x["mu"][k], max(x["alpha"][k], 1e-4)
            e = ref.lobe_terms(mu, alpha, max(2 * o.n, 1024))[0]
            dx.append(ref.l1_distance(mu, alpha, matrix(x, k), o.n, e)[0])
            dy.append(ref.l1_distance(mu, alpha, matrix(y, k), o.n, e)[0])
    dx, dy = np.array(dx), np.array(dy)
    ratio = dy / np.maximum(dx, 1e-9)
    print(f"texels {len(dx)} (rows every {o.step}, columns 2, {2 + o.step}, ...), n = {o.n}")
    print(f"before: median {np.median(dx):.5f} mean {np.mean(dx):.5f}")
    print(f"after:  median {np.median(dy):.5f} mean {np.mean(dy):.5f}")
    print("after / before: 1st, 10th, 50th, 90th, 99th percentile", np.round(np.percentile(ratio, [1, 10, 50, 90, 99]), 4))
    print(f"after worse by > 1%: {int(np.sum(ratio > 1.01))}, better by > 1%: {int(np.sum(ratio < 0.99))}")


if __name__ == "__main__":
    main()
