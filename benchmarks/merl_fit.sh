#!/bin/sh
# Issue 34 item 5: the time of `brdfbake fit` on a generated MERL file (GGX alpha = 0.3, Schlick
# f0 = 0.95, 0.64, 0.54 per channel, scripts/make_merl.py), fitted by ggx and beckmann with
# --fresnel schlick at --stride 2 (default) and 3, timed as whole processes by farm-bench; then
# one run each prints the fitted alpha, f0 and distance of the red channel. Then the fits of
# issue 34's later parameters: --fresnel conductor (eta, k) on the same file, and the
# anisotropic alpha_x, alpha_y of an analytic target; every row carries the standard errors.
# Usage: benchmarks/merl_fit.sh [path/to/brdfbake] [runs]   (writes nothing but /tmp files)
set -eu
exe=${1:-./build/brdfbake}
runs=${2:-1}
here=$(dirname "$0")
out=${TMPDIR:-/tmp}/brdfbake-merl-fit
mkdir -p "$out"
/usr/bin/python3 "$here/../scripts/make_merl.py" ggx --alpha 0.3 --f0 0.95,0.64,0.54 "$out/copperish.binary"
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores"
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
for model in ggx beckmann; do
    for stride in 2 3; do
        echo "== fit --model $model --fresnel schlick --stride $stride"
        farm-bench -n "$runs" --timeout 900 -- "$exe" fit --target "merl:file=$out/copperish.binary" \
            --model "$model" --fresnel schlick --stride "$stride" --format csv | grep -E "cpu s|wall s"
        "$exe" fit --target "merl:file=$out/copperish.binary" --model "$model" --fresnel schlick --stride "$stride" \
            --format csv | sed -n 2p
    done
done
echo "== fit --model ggx --fresnel conductor --stride 2"
farm-bench -n "$runs" --timeout 900 -- "$exe" fit --target "merl:file=$out/copperish.binary" \
    --model ggx --fresnel conductor --format csv | grep -E "cpu s|wall s"
"$exe" fit --target "merl:file=$out/copperish.binary" --model ggx --fresnel conductor --format csv | sed -n 2,4p
echo "== fit --target ggx:alpha_x=0.2,alpha_y=0.45 --model ggx --fresnel none (anisotropic, --stride 2)"
farm-bench -n "$runs" --timeout 900 -- "$exe" fit --target ggx:alpha_x=0.2,alpha_y=0.45 --model ggx --fresnel none \
    --format csv | grep -E "cpu s|wall s"
"$exe" fit --target ggx:alpha_x=0.2,alpha_y=0.45 --model ggx --fresnel none --format csv | sed -n 2,3p
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
