#!/bin/sh
# The pair of issue 20: the 32x32x16 rough dielectric table against the 128x128 GGX albedo table
# (the same number of texels) at --tolerance 1e-4, float and double, timed as whole processes in
# alternation by farm-bench (the ratio is taken run by run), with the machine named by lscpu.
# Usage: benchmarks/dielectric_pair.sh [path/to/brdfbake] [runs]   (writes nothing but /tmp files)
set -eu
exe=${1:-./build-new/brdfbake}
runs=${2:-3}
out=${TMPDIR:-/tmp}/brdfbake-dielectric-pair
mkdir -p "$out"
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; $("$exe" --version 2>/dev/null | head -1)"
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
for precision in float double; do
    echo "== $precision =="
    farm-bench -n "$runs" --warmup 1 --timeout 3000 \
        --vs "$exe lut albedo --model ggx --size 128x128 --tolerance 1e-4 --precision $precision -o $out/albedo-$precision.exr --no-preview" \
        -- "$exe" lut dielectric --model ggx --size 32x32x16 --eta-range 1,3 --tolerance 1e-4 --precision "$precision" \
        -o "$out/dielectric-$precision.exr" --no-preview
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
