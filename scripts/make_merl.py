#!/usr/bin/python3
"""Writes a MERL-format BRDF file (Matusik et al. 2003) from a known BRDF, for trying
`brdfbake ... --model merl:file=PATH` without the MERL database and for the tests.

  scripts/make_merl.py lambert --rho 0.5 lambert.binary
  scripts/make_merl.py ggx --alpha 0.3 --f0 0.9,0.6,0.3 ggx.binary
  scripts/make_merl.py ggx --alpha 0.2 --f0 0.04 --kd 0.5,0.2,0.1 plastic.binary

The format: three int32 dimensions (90, 90, 180), then the red, green and blue planes of
90*90*180 little-endian doubles, stored as f * 1500, f * 1500/1.15 and f * 1500/1.66. Bin
(ih, id, ip) holds f at its node, the bin's lower edge in Rusinkiewicz's half/difference angles
(Rusinkiewicz 1998): theta_h = (ih/90)^2 pi/2, theta_d = id pi/180, phi_d = ip pi/180, phi_h = 0.
Nodes with wo or wi below the horizon are written as -1, unmeasured, as in the MERL files
(lambert writes rho/pi there too, so that its albedo is rho at every direction: --holes marks them
unmeasured as ggx does).

ggx is the textbook GGX (Walter et al. 2007 eq. 33) with height-correlated Smith shadowing (Heitz
2014 eq. 99) and Schlick's Fresnel per channel, f0 = 1 (no Fresnel) by default: brdfbake's
`ggx:alpha=A` with `--fresnel none`. --kd adds a Lambert base kd/pi per channel (not multiplied
by the Fresnel term): brdfbake's `ggx:alpha=A,diffuse=KD`.
"""
import argparse
import struct
import sys

import numpy as np

SCALE = np.array([1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0])
NH, ND, NP = 90, 90, 180


def node_dirs():
    """wo, wi (each 3 x NH x ND x NP) at the bins' nodes."""
    ih, idd, ip = np.meshgrid(np.arange(NH), np.arange(ND), np.arange(NP), indexing="ij")
    th = (ih / NH) ** 2 * np.pi / 2
    td = idd / ND * np.pi / 2
    pd = ip / NP * np.pi
    d = np.stack([np.sin(td) * np.cos(pd), np.sin(td) * np.sin(pd), np.cos(td)])
    # wi = R_y(theta_h) d (phi_h = 0); wo the reflection of wi about h
    wi = np.stack([d[0] * np.cos(th) + d[2] * np.sin(th), d[1], -d[0] * np.sin(th) + d[2] * np.cos(th)])
    h = np.stack([np.sin(th), np.zeros_like(th), np.cos(th)])
    c = np.sum(wi * h, axis=0)
    wo = 2 * c * h - wi
    return wo, wi


def ggx(wo, wi, alpha):
    """D G2 / (4 cos_o cos_i), F = 1, for wo.z, wi.z > 0."""
    h = wo + wi
    h = h / np.linalg.norm(h, axis=0)
    a2 = alpha * alpha
    cos2 = h[2] ** 2
    d = a2 / (np.pi * (cos2 * (a2 - 1) + 1) ** 2)  # Walter et al. 2007 eq. 33

    def lam(w):  # Heitz 2014 eq. 86
        t2 = (1 - w[2] ** 2) / w[2] ** 2
        return (-1 + np.sqrt(1 + a2 * t2)) / 2

    g2 = 1 / (1 + lam(wo) + lam(wi))  # Heitz 2014 eq. 99
    return d * g2 / (4 * wo[2] * wi[2]), np.sum(wo * h, axis=0)


def write(path, rgb):
    """rgb: 3 x NH x ND x NP f values, negative for unmeasured."""
    stored = np.where(rgb < 0, -1.0, rgb / SCALE[:, None, None, None])
    with open(path, "wb") as out:
        out.write(struct.pack("<3i", NH, ND, NP))
        out.write(stored.astype("<f8").tobytes())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("model", choices=["lambert", "ggx"])
    ap.add_argument("output")
    ap.add_argument("--rho", default="1", help="lambert: albedo, one value or r,g,b")
    ap.add_argument("--alpha", type=float, default=0.3, help="ggx: roughness alpha")
    ap.add_argument("--f0", default="1", help="ggx: Schlick f0, one value or r,g,b")
    ap.add_argument("--kd", default="0", help="ggx: a Lambert base kd/pi, one value or r,g,b")
    ap.add_argument("--holes", action="store_true", help="lambert: mark nodes below the horizon unmeasured")
    a = ap.parse_args()
    wo, wi = node_dirs()
    below = (wo[2] <= 0) | (wi[2] <= 0)
    if a.model == "lambert":
        rho = np.broadcast_to(np.array([float(v) for v in a.rho.split(",")]), (3,))
        rgb = np.broadcast_to(rho[:, None, None, None] / np.pi, (3,) + wo.shape[1:]).copy()
        if a.holes:
            rgb[:, below] = -1
    else:
        f0 = np.broadcast_to(np.array([float(v) for v in a.f0.split(",")]), (3,))
        with np.errstate(all="ignore"):
            f, oh = ggx(wo, wi, a.alpha)
            fresnel = f0[:, None, None, None] + (1 - f0[:, None, None, None]) * (1 - oh) ** 5  # Schlick 1994
        kd = np.broadcast_to(np.array([float(v) for v in a.kd.split(",")]), (3,))
        rgb = np.where(below, -1.0, f * fresnel + kd[:, None, None, None] / np.pi)
    if not np.all(np.isfinite(rgb)):
        sys.exit("make_merl.py: error: non-finite values")
    write(a.output, rgb)


if __name__ == "__main__":
    main()
