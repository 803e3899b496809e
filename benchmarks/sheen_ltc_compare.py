#!/usr/bin/python3
"""Compare a `brdfbake lut sheen-ltc --preset cycles -o T.npy` table with Blender Cycles' shipped
table_sheen_ltc (intern/cycles/scene/shader.tables), a subset of whose rows the caller transcribes
into a Python file (never into this repository) defining dicts A, B, R: row j -> 32 values (row j is
roughness j/31, column i is mu i/31, both floored at 0.01).

Per texel with mu and roughness >= 0.1 (texels Cycles left unfitted, A = 0, skipped for the lobes): |R - R_cycles| and the L1 distance between the two LTC
densities (Heitz et al. 2016, M^-1 = [[a, 0, b], [0, a, 0], [0, 0, 1]]) over the upper hemisphere,
by a 512 x 512 midpoint rule in (theta, phi) (phi over [0, pi], doubled: both are symmetric).
Usage: sheen_ltc_compare.py TABLE.npy CYCLES_SUBSET.py"""
import runpy
import sys

import numpy as np


def ltc_density(a, b, x, y, z):
    u, v = a * x + b * z, a * y
    n = np.sqrt(u * u + v * v + z * z)
    return np.maximum(z / n, 0.0) / np.pi * a * a / n**3


def ltc_l1(a1, b1, a2, b2, n=512):
    th = (np.arange(n) + 0.5) / n * 0.5 * np.pi
    ph = (np.arange(n) + 0.5) / n * np.pi
    T, P = np.meshgrid(th, ph, indexing="ij")
    x, y, z = np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)
    w = np.sin(T) * (0.5 * np.pi / n) * (np.pi / n) * 2.0
    if a1 <= 0 or a2 <= 0:
        return float("nan")
    return float(np.sum(np.abs(ltc_density(a1, b1, x, y, z) - ltc_density(a2, b2, x, y, z)) * w))


def main():
    table = np.load(sys.argv[1])  # (roughness rows, mu columns, [a, b, R, distance, distance_error, error])
    ref = runpy.run_path(sys.argv[2])
    rows = []
    for j in sorted(ref["R"]):
        for i in range(32):
            if i / 31 < 0.1 or j / 31 < 0.1:
                continue
            a, b, r, dist = table[j, i][:4]
            err = table[j, i][-1]  # the error channel comes last
            ra, rb, rr = ref["A"][j][i], ref["B"][j][i], ref["R"][j][i]
            rows.append((j, i, r, err, rr, abs(r - rr), a, b, ra, rb, ltc_l1(a, b, ra, rb), dist))
    print("| j (roughness) | i (mu) | R | error | R Cycles | dR | a | b | A Cycles | B Cycles | L1(LTC, LTC Cycles) | distance |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for j, i, r, err, rr, dr, a, b, ra, rb, l1, dist in rows:
        print(f"| {j} ({j/31:.3f}) | {i} ({i/31:.3f}) | {r:.5f} | {err:.1e} | {rr:.5f} | {dr:.4f} | {a:.4f} | {b:.4f} "
              f"| {ra:.5f} | {rb:.5f} | {l1:.3f} | {dist:.3f} |")
    dr = np.array([x[5] for x in rows])
    l1 = np.array([x[10] for x in rows])
    print()
    print(f"texels: {len(rows)}; R within 0.01: {np.mean(dr <= 0.01) * 100:.1f}% (target 95%), "
          f"max |dR| {dr.max():.4f}, median {np.median(dr):.4f}")
    ok = ~np.isnan(l1)
    print(f"LTC lobes within L1 0.1: {np.mean(l1[ok] <= 0.1) * 100:.1f}% of {ok.sum()} (target 90%), "
          f"median L1 {np.median(l1[ok]):.3f}")
    print()
    print("| j (roughness) | texels | R within 0.01 | lobes within L1 0.1 | median L1 | max L1 |")
    print("|---|---|---|---|---|---|")
    for j in sorted(ref["R"]):
        sel = [x for x in rows if x[0] == j and not np.isnan(x[10])]
        if not sel:
            continue
        d = np.array([x[10] for x in sel])
        print(f"| {j} ({j/31:.3f}) | {len(sel)} | {sum(x[5] <= 0.01 for x in sel)} | {int(np.sum(d <= 0.1))} "
              f"| {np.median(d):.3f} | {d.max():.3f} |")


if __name__ == "__main__":
    main()
