#!/bin/sh
# Issue 35 item 6: the random walk's speed (walks per second) on the Smith microsurface
# (`albedo --model ggx|beckmann:alpha=0.5,scattering=multiple`, conductor and the rough
# dielectric with eta=1.5), float and double, from the kernel time that `brdfbake -v` prints
# (wall time: under load a floor) and from the process's CPU time (user + sys by /usr/bin/time,
# start-up and the cached kernel build included: on a shared machine the steadier figure); the
# machine named by lscpu, the load before and after.
# Usage: benchmarks/random_walk.sh [path/to/brdfbake] [walks]   (writes nothing)
set -eu
exe=${1:-./build/brdfbake}
walks=${2:-4194304}
cpu=$(mktemp)
trap 'rm -f "$cpu"' EXIT
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; $("$exe" --version 2>/dev/null | head -1)"
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "model         precision    walks    kernel s  walks/s (kernel)   CPU s  walks per CPU s"
for model in ggx beckmann ggx-eta beckmann-eta; do
    spec="${model%-eta}:alpha=0.5,scattering=multiple"
    [ "$model" = "${model%-eta}" ] || spec="$spec,eta=1.5"
    for precision in float double; do
        kernel=$(/usr/bin/time -o "$cpu" -f "%U %S" "$exe" -v albedo --model "$spec" --mu 0.5 --samples "$walks" \
            --precision "$precision" 2>&1 >/dev/null | sed -n 's/.*: kernel \([0-9.e+]*\) ms/\1/p')
        awk -v m="$model" -v p="$precision" -v n="$walks" -v k="$kernel" '{ c = $1 + $2;
            printf "%-13s %-6s %9d %10.3f %16.3g %8.2f %16.3g\n", m, p, n, k / 1e3, n / (k / 1e3), c, n / c }' "$cpu"
    done
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
