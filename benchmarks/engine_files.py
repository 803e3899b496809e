#!/usr/bin/python3
"""brdfbake's three.js DFGLUTData.js against the file three.js ships, texel by texel.

Writes `brdfbake lut --preset three -o DFGLUTData.js`, decodes its half floats (numpy float16), and
compares 16 texels (rows NoV j = 0, 5, 10, 15, columns roughness i = 0, 5, 10, 15) with the values
read from three.js's shipped src/renderers/shaders/DFGLUTData.js (mrdoob/three.js, 16 x 16 RG16F,
4096 samples per texel; read through the project's code search, not fetched, and not copied: only
these 32 half floats are written down here). Fetches nothing.

Usage: benchmarks/engine_files.py [path/to/brdfbake] > benchmarks/results/engine-files-MACHINE.md
"""
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

# (j, i): (A, B) as the shipped file's half-float bits; texel (i, j) at DATA[(j * 16 + i) * 2].
SHIPPED = {
    (0, 0): (0x30b5, 0x3ad1), (0, 5): (0x38d1, 0x3539), (0, 10): (0x3abf, 0x2e35), (0, 15): (0x3ae1, 0x28ff),
    (5, 0): (0x3b07, 0x2fca), (5, 5): (0x3ab4, 0x2e00), (5, 10): (0x39dc, 0x2707), (5, 15): (0x385f, 0x1fd1),
    (10, 0): (0x3bf6, 0x1cea), (10, 5): (0x3bb7, 0x1f25), (10, 10): (0x39da, 0x1cbd), (10, 15): (0x36b7, 0x1598),
    (15, 0): (0x3c00, 0x0000), (15, 5): (0x3bdd, 0x01df), (15, 10): (0x3a08, 0x075a), (15, 15): (0x3586, 0x049f),
}


def half(bits):
    return float(np.array([bits], dtype=np.uint16).view(np.float16)[0])


def main():
    exe = sys.argv[1] if len(sys.argv) > 1 else "build/brdfbake"
    with tempfile.TemporaryDirectory() as tmp:
        path = tmp + "/DFGLUTData.js"
        start = time.time()
        subprocess.run([exe, "lut", "--preset", "three", "-o", path, "--no-preview"], check=True)
        seconds = time.time() - start
        text = open(path).read()
    data = [int(h, 16) for h in re.findall(r"0x([0-9a-f]{4})", text.split("new Uint16Array")[1])]
    assert len(data) == 512, len(data)
    version = subprocess.run([exe, "--version"], capture_output=True, text=True).stdout.splitlines()[0]
    print("# brdfbake's DFGLUTData.js against three.js's shipped file\n")
    print(f"`{version}`, `lut --preset three -o DFGLUTData.js`: {seconds:.1f} s on this machine.\n")
    print("| NoV row j | roughness column i | shipped A | brdfbake A | shipped B | brdfbake B | max abs diff |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    worst = 0.0
    for (j, i), (sa, sb) in sorted(SHIPPED.items()):
        a, b = half(data[(j * 16 + i) * 2]), half(data[(j * 16 + i) * 2 + 1])
        d = max(abs(a - half(sa)), abs(b - half(sb)))
        worst = max(worst, d)
        print(f"| {j} | {i} | {half(sa):.5f} | {a:.5f} | {half(sb):.6f} | {b:.6f} | {d:.2e} |")
    max_error = re.search(r"max_error: (\S+)", text).group(1)
    print(f"\nLargest difference over the 16 texels: {worst:.2e}. brdfbake's own error estimate (max over the "
          f"table): {max_error}; three.js estimates each texel from 4096 samples and stores half floats "
          "(a step of 4.9e-4 between 0.5 and 1). Differences above both are where the two estimates of the "
          "same integral disagree (grazing NoV): there a 4096-sample estimate has a standard deviation of up to 3e-2 "
          "(benchmarks/three_dfg_noise.py, results/three-dfg-noise-MACHINE.md).")


if __name__ == "__main__":
    main()
