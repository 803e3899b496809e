#!/usr/bin/python3
"""Issue 33 item 6: a whole `lut ltc --preset unity-hdrp` C# file against `--preset three`'s table.

Usage: benchmarks/ltc_unity_compare.py LtcData.BRDF_GGX.cs three.csv
  (three.csv: `brdfbake lut ltc --preset three --mu-floor 3.7540224885647058e-4 -o three.csv`, HDRP's
  last-row floor, so that both grids hold the same (roughness, view)).
Reads the ushort array as HDRP's SetPixelData lays it (texel (a, t) at 4 (a + 64 t)), decodes the
half floats, and compares them with three.js's ltc_1 = (M^-1_00, M^-1_20, M^-1_02, M^-1_22) / M^-1_11
renormalised as HDRP's generator does, (M^-1_00, M^-1_20, M^-1_11, M^-1_02) / M^-1_22 = (R, G, 1, B) / A,
clamped to 65504 (docs/ltc_presets.md, "Unity HDRP"). Prints the largest relative deviation (the
half's rounding is 2^-11 = 4.88e-4), the clamped entries and a few texels.
"""
import csv
import re
import sys

import numpy as np


def hdrp_texels(path):
    text = open(path).read()
    body = re.sub(r"//[^\n]*", "", text[text.index("{", text.index("new ushort")):])
    bits = np.array([int(x) for x in re.findall(r"\d+", body)], dtype=np.uint16)
    n = int(round((bits.size / 4) ** 0.5))
    return bits.view(np.float16).astype(np.float64).reshape(n, n, 4)


def three_texels(path, n):
    rows = list(csv.DictReader(r for r in open(path) if not r.startswith("#")))
    return np.array([[float(r["ltc_1." + c]) for c in "RGBA"] for r in rows]).reshape(n, n, 4)


def main():
    u = hdrp_texels(sys.argv[1])
    n = u.shape[0]
    r, g, b, a = np.moveaxis(three_texels(sys.argv[2], n), -1, 0)
    want = np.clip(np.stack([r / a, g / a, 1 / a, b / a], -1), -65504, 65504)
    normal = np.abs(want) >= 2.0**-14
    rel = np.abs(u - want)[normal] / np.abs(want)[normal]
    print(f"{n} x {n} texels: largest relative deviation {rel.max():.3g} over {normal.sum()} entries "
          f"(half rounding 2^-11 = {2.0**-11:.3g}); below the half's normal range largest absolute "
          f"{np.abs(u - want)[~normal].max() if (~normal).any() else 0:.3g}")
    print(f"entries clamped to 65504: {(np.abs(u) == 65504).sum()}; texels with B <= 0: {(u[..., 2] <= 0).sum()}")
    for t, a_ in [(0, 1), (0, 2), (0, n - 1), (1, 2), (n - 1, n - 1)]:
        print(f"t = {t}, a = {a_}: " + ", ".join(f"{v:.6g}" for v in u[t, a_]))


if __name__ == "__main__":
    main()
