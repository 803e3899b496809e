#!/bin/sh
# Issue 34 item 7: a measured material against the analytic model on the same cells at
# --tolerance 1e-4. The file is GGX alpha = 0.3 written by scripts/make_merl.py (nodes below the
# horizon unmeasured, as in MERL's files); the yardstick is ggx:alpha=0.3 on the same 11
# directions. Each lookup (nearest, linear) is timed as a whole process by farm-bench in
# alternation with the yardstick (the ratio survives a loaded machine); then one run each prints
# the albedo's device seconds and samples (--format json). The issue's target: within 2x.
# Usage: benchmarks/merl_speed.sh [path/to/brdfbake] [runs]   (writes nothing but /tmp files)
set -eu
exe=${1:-./build/brdfbake}
runs=${2:-3}
here=$(dirname "$0")
out=${TMPDIR:-/tmp}/brdfbake-merl-speed
mkdir -p "$out"
/usr/bin/python3 "$here/../scripts/make_merl.py" ggx --alpha 0.3 "$out/ggx.binary"
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; $("$exe" --version 2>/dev/null | head -1)"
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
mu=0.05,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1
for interp in linear nearest; do
    echo "== merl interp=$interp against ggx:alpha=0.3, --tolerance 1e-4, 11 directions"
    farm-bench -n "$runs" --warmup 1 --timeout 900 \
        --vs "$exe albedo --model ggx:alpha=0.3 --mu $mu --tolerance 1e-4" \
        -- "$exe" albedo --model "merl:file=$out/ggx.binary,interp=$interp" --mu "$mu" --tolerance 1e-4
done
for spec in "ggx:alpha=0.3" "merl:file=$out/ggx.binary,interp=linear" "merl:file=$out/ggx.binary,interp=nearest"; do
    "$exe" albedo --model "$spec" --mu "$mu" --tolerance 1e-4 --format json 2>/dev/null |
        /usr/bin/python3 -c "import json,sys; j=json.load(sys.stdin); print('%-60s device %.3f s, %d samples, %d rounds' % (j['model'], j['seconds'], j['total_samples'], j['rounds']))"
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
