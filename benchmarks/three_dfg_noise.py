#!/usr/bin/python3
"""Why three.js's shipped DFGLUTData.js differs from brdfbake's at its grazing row: a measurement.

three.js's file (mrdoob/three.js src/renderers/shaders/DFGLUTData.js, 16 x 16 RG16F, header "Samples:
4096 per texel") ships without its generator (not in the repository; PRs #32054 and #32358 do not
include it). Its row 0 decodes as NoV = 1/32 (texel centres: at roughness column 0 the bias B is
0.852051 = (1 - 1/32)^5 to half-float precision) and its columns as roughness (i + 0.5)/16 (B matches
brdfbake's to 3e-4 along the row). The scale A of row 0 differs by up to 1.4e-2 (column 5).

This script measures, at the 16 texels benchmarks/engine_files.py compares (the shipped half floats
are taken from there), with numpy only:
  - the converged (A, B) of the split-sum definition (height-correlated Smith GGX, alpha =
    roughness^2, Schlick weight (1 - VoH)^5), by visible-normal sampling (Heitz 2018) over 2^18
    Hammersley points, whose weight G2/G1 is bounded (its difference from 2^16 points is printed);
  - the standard deviation of a 4096-sample estimate of A drawn as the common generators draw it
    (half vectors from D cos(theta_h), Karis 2013, weight G_vis = 4 V NoL VoH / NoH) with random
    points, over 200 independent sets: the noise of a file made that way;
  - the shipped value's distance from the converged one in those standard deviations.
Fetches nothing, writes nothing but stdout.

Usage: benchmarks/three_dfg_noise.py > benchmarks/results/three-dfg-noise-MACHINE.md
"""
import sys
import time

import numpy as np

from engine_files import SHIPPED, half


def hammersley(n):
    i = np.arange(n, dtype=np.uint64)
    b = i.copy()
    for shift, mask in ((16, 0xFFFFFFFF), (1, 0x55555555), (2, 0x33333333), (4, 0x0F0F0F0F), (8, 0x00FF00FF)):
        if shift == 16:
            b = ((b << 16) | (b >> 16)) & mask
        else:
            b = ((b & mask) << shift) | ((b >> shift) & mask)
    return i / n, b.astype(np.float64) * 2.0**-32


def lam(a, c):
    """Smith Lambda of GGX."""
    return 0.5 * (-1 + np.sqrt(1 + a * a * (1 - c * c) / (c * c)))


def vndf(nv, r, u1, u2):
    """(A, B) by visible-normal sampling: each sample's weight is G2 / G1(v), bounded by 1."""
    a = r * r
    v = np.array([np.sqrt(1 - nv * nv), 0.0, nv])
    vh = np.array([a * v[0], 0.0, v[2]]) / np.hypot(a * v[0], v[2])
    t1 = np.array([0.0, 1.0, 0.0])  # vh lies in the xz plane
    t2 = np.cross(vh, t1)
    rad, phi = np.sqrt(u1), 2 * np.pi * u2
    p1, p2 = rad * np.cos(phi), rad * np.sin(phi)
    s = 0.5 * (1 + vh[2])
    p2 = (1 - s) * np.sqrt(1 - p1 * p1) + s * p2
    p3 = np.sqrt(np.clip(1 - p1 * p1 - p2 * p2, 0, None))
    nh = p1[None] * t1[:, None] + p2[None] * t2[:, None] + p3[None] * vh[:, None]
    h = np.stack([a * nh[0], a * nh[1], np.clip(nh[2], 0, None)])
    h /= np.linalg.norm(h, axis=0)
    voh = v @ h
    nl = 2 * voh * h[2] - nv
    m = nl > 0
    w = (1 + lam(a, nv)) / (1 + lam(a, nv) + lam(a, nl[m]))
    fc = (1 - voh[m]) ** 5
    return ((1 - fc) * w).sum() / len(u1), (fc * w).sum() / len(u1)


def karis_a(nv, r, u1, u2):
    """A by half vectors drawn from D cos(theta_h): sum of (1 - Fc) 4 V NoL VoH / NoH over N."""
    a = r * r
    ct = np.sqrt((1 - u2) / (1 + (a * a - 1) * u2))
    st = np.sqrt(1 - ct * ct)
    phi = 2 * np.pi * u1
    voh = np.sqrt(1 - nv * nv) * st * np.cos(phi) + nv * ct
    nl = 2 * voh * ct - nv
    m = nl > 0
    a2 = a * a
    vis = 0.5 / (nl[m] * np.sqrt(a2 + (1 - a2) * nv * nv) + nv * np.sqrt(a2 + (1 - a2) * nl[m] ** 2))
    return ((1 - (1 - voh[m]) ** 5) * 4 * vis * nl[m] * voh[m] / ct[m]).sum() / len(u1)


def main():
    start = time.time()
    rng = np.random.default_rng(2026)
    fine, coarse = hammersley(1 << 18), hammersley(1 << 16)
    print("# three.js's DFGLUTData.js: its grazing row against the noise of a 4096-sample estimate\n")
    print("`benchmarks/three_dfg_noise.py` (numpy only). NoV = (j + 0.5)/16, roughness = (i + 0.5)/16, "
          "alpha = roughness^2, height-correlated Smith GGX.\n")
    print("| NoV row j | roughness column i | shipped A | converged A | its error | shipped - converged | "
          "sd of a 4096-sample A | in sd | shipped B | converged B |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for (j, i), (sa, sb) in sorted(SHIPPED.items()):
        nv, r = (j + 0.5) / 16, (i + 0.5) / 16
        a, b = vndf(nv, r, *fine)
        a_err = abs(a - vndf(nv, r, *coarse)[0])
        sd = np.std([karis_a(nv, r, rng.random(4096), rng.random(4096)) for _ in range(200)])
        d = half(sa) - a
        print(f"| {j} | {i} | {half(sa):.5f} | {a:.5f} | {a_err:.1e} | {d:+.2e} | {sd:.2e} | "
              f"{d / sd if sd > 0 else 0:+.2f} | {half(sb):.6f} | {b:.6f} |")
    print("\nRow 0 by 4096-point Hammersley sets, the deterministic kind a shader generator uses: the same "
          "estimator (half vectors from D cos(theta_h)) with its radical inverse u or 1 - u driving theta_h.\n")
    print("| roughness column i | shipped A | converged A | Hammersley, u | Hammersley, 1 - u |")
    print("| --- | --- | --- | --- | --- |")
    u1, u2 = hammersley(4096)
    for i in (0, 5, 10, 15):
        r = (i + 0.5) / 16
        print(f"| {i} | {half(SHIPPED[(0, i)][0]):.5f} | {vndf(1 / 32, r, *fine)[0]:.5f} | "
              f"{karis_a(1 / 32, r, u1, u2):.5f} | {karis_a(1 / 32, r, u1, 1 - u2):.5f} |")
    print(f"\n{time.time() - start:.0f} s on this machine.", file=sys.stderr)


if __name__ == "__main__":
    main()
