#!/bin/sh
# Issue 33 item 5: the 64x64 GGX LTC table (`brdfbake lut ltc --model ggx --size 64x64`), timed as
# a whole process by farm-bench against the yardstick of the same grid's albedo table (its
# magnitude channel alone), run in alternation so that the ratio survives a loaded machine; the
# machine named by lscpu, the load before and after. The issue's reference: Heitz and Hill's
# fitLTC takes 92 s of CPU for the same table on this project's 2-core machine.
# Usage: benchmarks/ltc_table.sh [path/to/brdfbake] [runs]   (writes nothing but /tmp files)
set -eu
exe=${1:-./build/brdfbake}
runs=${2:-3}
out=${TMPDIR:-/tmp}/brdfbake-ltc-table
mkdir -p "$out"
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; $("$exe" --version 2>/dev/null | head -1)"
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
farm-bench -n "$runs" --warmup 1 --timeout 600 \
    --vs "$exe lut albedo --model ggx --size 64x64 -o $out/albedo.exr --no-preview" \
    -- "$exe" lut ltc --model ggx --size 64x64 -o "$out/ltc.exr" --no-preview
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
"$exe" show "$out/ltc.exr" 2>/dev/null | grep -E "distance" || true
