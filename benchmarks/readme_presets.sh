#!/bin/sh
# Issue 30: every preset command of the README, run once at its default settings with
# --no-preview, its exit status and wall time; every .h (and EEVEE's .c) it writes compiled as C and C++, a .cc as C++,
# a .cs (Unity HDRP) as C# by Mono's mcs.
# Usage: benchmarks/readme_presets.sh [path/to/brdfbake]   (writes only under $TMPDIR)
set -u
exe=$(realpath "${1:-./build/brdfbake}")
out=${TMPDIR:-/tmp}/brdfbake-readme-presets
rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load at start $(cut -d' ' -f1-3 /proc/loadavg)"
echo "| command | exit | wall | header compiles (C, C++) |"
echo "| --- | --- | --- | --- |"
while IFS='|' read -r args file; do
    [ -z "$args" ] && continue
    start=$(date +%s.%N)
    # shellcheck disable=SC2086
    "$exe" lut $args --no-preview -o "$file" >/dev/null 2>"$file.err"
    rc=$?
    wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
    compiles=-
    case "$file" in *.h)
        c=no; cxx=no
        echo "#include \"$file\"" | gcc -fsyntax-only -x c - 2>/dev/null && c=yes
        echo "#include \"$file\"" | g++ -fsyntax-only -x c++ - 2>/dev/null && cxx=yes
        compiles="$c, $cxx" ;;
    *.cc)  # Blender EEVEE (4.2 and later): C++ only
        cxx=no
        g++ -std=c++17 -fsyntax-only "$file" 2>/dev/null && cxx=yes
        compiles="-, $cxx" ;;
    *.c)  # legacy EEVEE: C and C++
        c=no; cxx=no
        gcc -std=c99 -fsyntax-only "$file" 2>/dev/null && c=yes
        g++ -fsyntax-only -x c++ "$file" 2>/dev/null && cxx=yes
        compiles="$c, $cxx" ;;
    *.cs)  # Unity HDRP: C#, compiled alone as a library by Mono's mcs (mono-mcs)
        cs=no
        mcs -nologo -target:library -warnaserror+ -out:"$file.dll" "$file" >/dev/null 2>&1 && cs=yes
        compiles="C#: $cs" ;;
    esac
    printf '| `lut %s -o %s` | %s | %.1f s | %s |\n' "$args" "$file" "$rc" "$wall" "$compiles"
done <<'LIST'
--preset cycles|ggx_E.h
eavg --preset cycles|ggx_Eavg.h
dielectric --preset cycles|ggx_glass_E.h
dielectric-eavg --preset cycles|ggx_glass_Eavg.h
gen-schlick --preset cycles|ggx_gen_schlick_s.h
gen-schlick --preset cycles --estimator cycles|ggx_gen_schlick_s_cycles.h
gen-schlick-ior --preset cycles|ggx_gen_schlick_ior_s.h
gen-schlick-ior --preset cycles --estimator cycles|ggx_gen_schlick_ior_s_cycles.h
--preset gltf|lut_ggx.png
sheen-viewer --preset gltf|lut_sheen_E.png
sheen-viewer --preset gltf --model sheen:visibility=ashikhmin|lut_charlie.png
--preset filament|dfg.exr
--preset three|DFGLUTData.js
ltc --preset three|ltc_three.exr
ltc --preset eevee|eevee_ltc.cc
ltc --preset unity-hdrp|LtcData.BRDF_GGX.cs
ltc --preset unity-hdrp-2021|LtcData.BRDF_GGX_2021.cs
--preset unreal|PreIntegratedGF.png
LIST
echo "load at end $(cut -d' ' -f1-3 /proc/loadavg)"
