#!/bin/sh
# Issue 35 item 6: the random walk's speed (walks per second) on the Smith microsurface
# (`albedo --model ggx|beckmann:alpha=0.5,scattering=multiple`, conductor and the rough
# dielectric with eta=1.5), float and double, from the
# kernel time that `brdfbake -v` prints; the machine named by lscpu, the load before and after.
# Usage: benchmarks/random_walk.sh [path/to/brdfbake] [walks]   (writes nothing)
set -eu
exe=${1:-./build/brdfbake}
walks=${2:-4194304}
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; $("$exe" --version 2>/dev/null | head -1)"
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
for model in ggx beckmann ggx-eta beckmann-eta; do
    spec="${model%-eta}:alpha=0.5,scattering=multiple"
    [ "$model" = "${model%-eta}" ] || spec="$spec,eta=1.5"
    for precision in float double; do
        "$exe" -v albedo --model "$spec" --mu 0.5 --samples "$walks" \
            --precision "$precision" 2>&1 >/dev/null |
            sed -n 's/.*: kernel \([0-9.e+]*\) ms/\1/p' |
            awk -v m="$model" -v p="$precision" -v n="$walks" \
                '{ printf "%-13s %-6s %9d walks %9.3f s kernel %10.3g walks/s\n", m, p, n, $1 / 1e3, n / ($1 / 1e3) }'
    done
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
