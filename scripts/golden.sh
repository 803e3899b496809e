#!/usr/bin/env bash
# The golden set of a refactoring: every README command that writes numbers, run with fixed
# seeds, in float and double, into DIR. Run it on the commit before a change and after it, then
# compare the two folders with `scripts/golden.sh --compare OLD NEW`: tables must be
# bit-identical (CSV text, EXR channel data) and JSON outputs equal but for timings and paths.
# Usage: scripts/golden.sh BRDFBAKE DIR        (BRDFBAKE: the executable, e.g. build/brdfbake)
#        scripts/golden.sh --compare OLD NEW
set -uo pipefail

if [ "${1:-}" = "--compare" ]; then
  old=$2 new=$3
  /usr/bin/python3 - "$old" "$new" <<'EOF'
import json, os, re, sys
old, new = sys.argv[1], sys.argv[2]
# Timings, and the checkout's own path (a scene file is named by its absolute path).
volatile = {"seconds", "kernel_seconds", "wall_seconds", "build_seconds", "device", "elapsed", "time", "path",
            "output", "outputs", "tool", "created", "scene"}
def timeless(text):
    return re.sub(rb"[0-9.]+(e-?[0-9]+)? ?(ms|s)\b", b"T", text)
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if k not in volatile and not k.endswith("_seconds")}
    if isinstance(x, list):
        return [strip(v) for v in x]
    return x
bad = 0
names = sorted(set(os.listdir(old)) | set(os.listdir(new)))
for n in names:
    a, b = os.path.join(old, n), os.path.join(new, n)
    if not (os.path.exists(a) and os.path.exists(b)):
        print("missing on one side:", n); bad += 1; continue
    da, db = open(a, "rb").read(), open(b, "rb").read()
    if n.endswith(".json"):
        try:
            same = strip(json.loads(da)) == strip(json.loads(db))
        except ValueError:
            same = da == db
    elif n.endswith(".err"):
        same = timeless(da) == timeless(db)
    elif n.endswith(".exr"):
        same = open(a + ".dump", "rb").read() == open(b + ".dump", "rb").read() if os.path.exists(a + ".dump") else da == db
    else:
        same = da == db
    if not same:
        print("differs:", n); bad += 1
print(f"{len(names) - bad} of {len(names)} outputs identical")
sys.exit(1 if bad else 0)
EOF
  exit $?
fi

exe=$(realpath "$1") dir=$2
mkdir -p "$dir"
cd "$dir" || exit 2
n=0
run() {  # run NAME ARGS...: stdout to NAME, exit status to NAME.rc
  local name=$1; shift
  "$exe" "$@" > "$name" 2> "$name.err"; echo $? > "$name.rc"
  n=$((n + 1))
}
for p in float double; do
  run albedo-mu-$p.csv albedo --model ggx:alpha=0.5 --mu 0.1,0.5,1 --precision $p --format csv
  run albedo-json-$p.json albedo --model ggx:alpha=0.5 --mu 0.5 --format json --precision $p
  run albedo-al-$p.csv albedo --model ggx:alpha=0.5 --fresnel metal:Al --wavelength 550 --precision $p --format csv
  run albedo-aniso-$p.csv albedo --model ggx:alpha_x=0.1,alpha_y=0.6 --mu 0.3 --phi 0,45,90 --precision $p --format csv
  for m in lambert oren-nayar:sigma=0.5 phong:n=20 phong-original:n=20 blinn-phong:n=20 torrance-sparrow \
           torrance-sparrow:d=blinn,n=50 beckmann:alpha=0.3 mirror dielectric-specular:eta=1.5 ggx:alpha=0.05; do
    case $m in torrance-sparrow) m=torrance-sparrow:alpha=0.3 ;; esac
    for meth in importance qmc mc quadrature; do
      run "albedo-${m%%:*}-$(echo "$m" | tr ':=,' '___')-$meth-$p.csv" albedo --model "$m" --mu 0.05,0.5,1 --method $meth \
        --samples 65536 --precision $p --format csv
    done
  done
  run albedo-tol1-$p.csv albedo --model ggx:alpha=0.001 --mu 0.1 --tolerance 1e-5 --precision double --format csv
  run albedo-tol2-$p.json albedo --model ggx:alpha=0.5 --mu 0.001,0.5 --tolerance 1e-5 --format json --precision double
  run lut-albedo-tol-$p.csv lut albedo --model ggx --size 16x16 --tolerance 1e-5 --precision double -o lut-albedo-tol-$p.out.csv
  run lut-albedo-$p.csv lut albedo --model ggx --size 16x16 --precision $p -o lut-albedo-$p.out.csv
  run lut-eavg-$p.csv lut eavg --model ggx --size 16 --precision $p -o lut-eavg-$p.out.csv
  run lut-dfg-$p.csv lut dfg --model ggx --size 16x16 --mu-map sqrt --precision $p -o lut-dfg-$p.out.csv
  run lut-dfgms-$p.csv lut dfg-ms --model ggx:shadowing=separable --size 16x16 --precision $p -o lut-dfgms-$p.out.h
  run lut-diel-$p.csv lut dielectric --model ggx --size 8x8x4 --eta-range 1,3 --samples 16384 --precision $p -o lut-diel-$p.out.csv
  run lut-diel-tol-$p.csv lut dielectric --model ggx --size 4x4x2 --eta-range 1,3 --tolerance 1e-3 --precision $p -o lut-diel-tol-$p.out.csv
  run lut-cond-$p.csv lut conductor --model ggx --fresnel metal:Au --size 8x8 --precision $p -o lut-cond-$p.out.csv
  run lut-beck-$p.csv lut albedo --model beckmann --size 8x8 --tolerance 1e-4 --precision $p -o lut-beck-$p.out.csv
  run lut-ts-$p.csv lut albedo --model torrance-sparrow --size 8x8 --tolerance 1e-4 --precision $p -o lut-ts-$p.out.csv
  run fresnel-al-$p.csv fresnel --fresnel metal:Al --wavelength 550 --theta 0,30,60,75,85,89 --precision $p --format csv
  run fresnel-diel-$p.json fresnel --fresnel dielectric:eta=1.5 --format json --precision $p
  run check-ggx-$p.json check --model ggx:alpha=0.5 --format json --precision $p
  run check-lambert-$p.json check --model lambert:rho=1.2 --format json --precision $p
done
run plan-json.json plan "$OLDPWD/examples/scene.json" --format json
run plan-gltf.json plan "$OLDPWD/examples/scene.gltf" --format json
run bake.txt bake "$OLDPWD/examples/scene.json" -o bake-out
for f in bake-out/*; do cp "$f" "bake-$(basename "$f")"; done
rm -rf bake-out
echo "golden: $n commands into $dir"
