#!/usr/bin/env bash
# `plan`'s estimate against the bake's real time (issue 32: within 1.5x both ways).
# Usage: benchmarks/plan_estimates.sh BRDFBAKE [SCENE...]
# Prints a Markdown table: scene, plan's estimate, the bake's wall and CPU seconds (the run of median
# wall time of RUNS, default 3), wall/estimate.
# Each bake runs with --force into a fresh folder (previews and report on, as `bake` does by
# default), under `nice -n -20` when run as root so that other jobs on a shared machine do not
# inflate the wall time (record the machine and its load beside the numbers: benchmarks/results/);
# the plans run under the same nice, so that their probe measures what the bakes will get.
# Not a test: timings depend on the machine. The estimates use the calibration file
# (BRDFBAKE_CALIBRATION, docs/scenes.md "Estimates"), into which these bakes record too; the
# column "basis" says whether the plan was calibrated. CALIBRATE=1 first bakes every scene once
# (recording into the file) before measuring; BUILTIN=1 measures the built-in figures as a first
# bake meets them (no calibration file yet: each plan is given a fresh path, so it measures the
# machine's slowdown as `plan` does, and each bake a fresh one too). Each plan measures how much
# slower than idle cores the machine runs (BRDFBAKE_SLOWDOWN overrides; calibration.h).
# COLD=1: PoCL's kernel cache cold (a fresh POCL_CACHE_DIR that the plan and then one bake share,
# as a first bake after `plan` meets it; RUNS is then 1). The column "bake's tables / plan's" is
# the sum of the per-table estimates the bake's log printed over the plan's for the same tables.
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
[ "${COLD:-0}" = 1 ] && runs=1
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
echo "| scene | plan estimate (s) | bake wall (s) | bake CPU (s) | wall / estimate | estimate / wall | basis | bake's tables / plan's | load average |"
echo "| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
for s in "${scenes[@]}"; do
  extra=()
  case "$s" in *@*) extra=(${s#*@}); s=${s%%@*} ;; esac
  plan_env=(env)
  [ "${BUILTIN:-0}" = 1 ] && plan_env+=(BRDFBAKE_CALIBRATION="$work/none-$RANDOM.json")
  [ "${COLD:-0}" = 1 ] && plan_env+=(POCL_CACHE_DIR="$work/pocl-$RANDOM")
  IFS=' ' read -r est tables basis < <("${plan_env[@]}" "${nice[@]}" "$exe" plan "$s" "${extra[@]}" --format json | /usr/bin/python3 -c 'import json,re,sys; e = json.load(sys.stdin)["estimate"]; m = re.search(r"times ([0-9.]+)", e["basis"]); print("%.2f" % e["seconds"], "%.3f" % e["integration_seconds"], ("calibrated" if e["basis"].startswith("calibrated") else "built-in") + ", slowdown " + (m.group(1) if m else "1") + (", cold cache" if e.get("kernel_cache_cold") else ""))')
  load=$(cut -d' ' -f1 /proc/loadavg)
  : >"$work/times"
  for _ in $(seq "$runs"); do
    bake_env=("${plan_env[@]}")
    [ "${BUILTIN:-0}" = 1 ] && bake_env+=(BRDFBAKE_CALIBRATION="$work/none-$RANDOM.json")
    /usr/bin/time -f "%e %U %S" -o "$work/time" "${bake_env[@]}" "${nice[@]}" "$exe" bake "$s" "${extra[@]}" --force -o "$work/out" 2>"$work/log" >/dev/null ||
      { echo "bake of $s failed:"; tail -3 "$work/log"; exit 1; }
    # The bake's own per-table estimates (its log's "(estimate X s)") over the plan's.
    bake_tables=$(grep -o '(estimate [0-9.]* s)' "$work/log" | tr -dc '0-9.\n' | paste -sd+ | /usr/bin/python3 -c "import sys; t = sys.stdin.read().strip(); print('%.2f' % (eval(t or '0') / max($tables, 1e-9)))")
    echo "$(cat "$work/time") $bake_tables" >>"$work/times"
    rm -rf "$work/out"
  done
  # The run of median wall time.
  read -r wall user sys agree < <(sort -n "$work/times" | sed -n "$(( (runs + 1) / 2 ))p")
  cpu=$(/usr/bin/python3 -c "print('%.2f' % ($user + $sys))")
  ratio=$(/usr/bin/python3 -c "print('%.2f' % ($wall / $est))")
  inverse=$(/usr/bin/python3 -c "print('%.2f' % ($est / $wall))")
  echo "| \`${s#$here/}\` ${extra[*]} | $est | $wall | $cpu | $ratio | $inverse | $basis | $agree | $load |"
done
