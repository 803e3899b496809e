#!/usr/bin/env bash
# `plan`'s estimate against the bake's real time (issue 32: within 1.5x both ways).
# Usage: benchmarks/plan_estimates.sh BRDFBAKE [SCENE...]
# Prints a Markdown table: scene, plan's estimate, the bake's wall and CPU seconds (the run of median
# wall time of RUNS, default 3), wall/estimate.
# Each bake runs with --force into a fresh folder (previews and report on, as `bake` does by
# default), under `nice -n -20` when run as root so that other jobs on a shared machine do not
# inflate the wall time (record the machine and its load beside the numbers: benchmarks/results/).
# Not a test: timings depend on the machine. The estimates use the calibration file
# (BRDFBAKE_CALIBRATION, docs/scenes.md "Estimates"), into which these bakes record too; the
# column "basis" says whether the plan was calibrated. CALIBRATE=1 first bakes every scene once
# (recording into the file) before measuring; BUILTIN=1 measures the built-in figures as a first
# bake meets them (no calibration file yet: each plan is given a fresh path, so it measures the
# machine's slowdown as `plan` does, and the bakes record nothing). Each plan measures how much
# slower than idle cores the machine runs (BRDFBAKE_SLOWDOWN overrides; calibration.h).
set -euo pipefail
exe=$(realpath "${1:?usage: plan_estimates.sh BRDFBAKE [SCENE...]}")
shift
here=$(cd "$(dirname "$0")/.." && pwd)
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  scenes=("$here/examples/scene.json" "$here/examples/scene.gltf" "$here/tests/data/materials.gltf"
          "$here/tests/data/small_glass.json" "$here/tests/data/metals_glass.json")
fi
runs=${RUNS:-3}
nice=()
[ "$(id -u)" -eq 0 ] && nice=(nice -n -20)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ "${CALIBRATE:-0}" = 1 ]; then
  for s in "${scenes[@]}"; do
    extra=()
    case "$s" in *@*) extra=(${s#*@}); s=${s%%@*} ;; esac
    "$exe" bake "$s" "${extra[@]}" --force -o "$work/out" 2>/dev/null >/dev/null || { echo "bake of $s failed"; exit 1; }
    rm -rf "$work/out"
  done
fi
echo "| scene | plan estimate (s) | bake wall (s) | bake CPU (s) | wall / estimate | estimate / wall | basis | load average |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
for s in "${scenes[@]}"; do
  extra=()
  case "$s" in *@*) extra=(${s#*@}); s=${s%%@*} ;; esac
  plan_env=()
  [ "${BUILTIN:-0}" = 1 ] && plan_env=(env BRDFBAKE_CALIBRATION="$work/none-$RANDOM.json")
  IFS=' ' read -r est basis < <("${plan_env[@]}" "$exe" plan "$s" "${extra[@]}" --format json | /usr/bin/python3 -c 'import json,re,sys; e = json.load(sys.stdin)["estimate"]; m = re.search(r"times ([0-9.]+)", e["basis"]); print("%.2f" % e["seconds"], ("calibrated" if e["basis"].startswith("calibrated") else "built-in") + ", slowdown " + (m.group(1) if m else "1"))')
  load=$(cut -d' ' -f1 /proc/loadavg)
  : >"$work/times"
  for _ in $(seq "$runs"); do
    bake_env=()
    [ "${BUILTIN:-0}" = 1 ] && bake_env=(env BRDFBAKE_CALIBRATION=off)
    /usr/bin/time -f "%e %U %S" -o "$work/time" "${bake_env[@]}" "${nice[@]}" "$exe" bake "$s" "${extra[@]}" --force -o "$work/out" 2>"$work/log" >/dev/null ||
      { echo "bake of $s failed:"; tail -3 "$work/log"; exit 1; }
    cat "$work/time" >>"$work/times"
    rm -rf "$work/out"
  done
  # The run of median wall time.
  read -r wall user sys < <(sort -n "$work/times" | sed -n "$(( (runs + 1) / 2 ))p")
  cpu=$(/usr/bin/python3 -c "print('%.2f' % ($user + $sys))")
  ratio=$(/usr/bin/python3 -c "print('%.2f' % ($wall / $est))")
  inverse=$(/usr/bin/python3 -c "print('%.2f' % ($est / $wall))")
  echo "| \`${s#$here/}\` ${extra[*]} | $est | $wall | $cpu | $ratio | $inverse | $basis | $load |"
done
