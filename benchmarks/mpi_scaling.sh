#!/usr/bin/env bash
# Strong scaling of MPI jobs (docs/cluster.md): a 3D dielectric table and a 2D tolerance-mode
# albedo table at 1, 2 and 4 ranks (4 oversubscribed on a 2-core machine), every rank running
# PoCL on one thread, for the cyclic and the block split of cells. Checks that every file equals
# the one-rank file byte for byte and writes a Markdown record.
# Usage: benchmarks/mpi_scaling.sh [BRDFBAKE] [RECORD.md]
set -euo pipefail
exe=${1:-build-new/brdfbake}
record=${2:-benchmarks/results/mpi-scaling.md}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export POCL_MAX_PTHREAD_COUNT=1 BRDFBAKE_MPI_STATS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

declare -A tables=(
  [dielectric]="lut dielectric --model ggx --size 12x12x6 --samples 8192"
  [tolerance]="lut albedo --model torrance-sparrow --size 16x16 --tolerance 1e-4"
)

{
  echo "# Strong scaling of MPI jobs ($(date -u +%Y-%m-%d))"
  echo
  echo "Machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs ($(lscpu | sed -n 's/^Thread(s) per core: *//p') threads per core); shared with other work while measured."
  echo "Open MPI $(mpirun --version | head -1 | awk '{print $NF}'), PoCL with POCL_MAX_PTHREAD_COUNT=1 per rank; brdfbake $($exe --version | awk '{print $2}')."
  echo "Wall time of the whole command (start-up, kernel builds, compute, gathers, write); 'in steps' is rank 0's time"
  echo "inside the all-gathers, which includes waiting for the slowest rank. Efficiency = t1 / (N tN)."
  echo
  echo "| table | split | ranks | wall s | efficiency | steps | bytes gathered | s in steps | identical to 1 rank |"
  echo "|---|---|---|---|---|---|---|---|---|"
} > "$work/record.md"

for name in dielectric tolerance; do
  args=${tables[$name]}
  t1=""
  for split in cyclic block; do
    for np in 1 2 4; do
      [ "$np" = 1 ] && [ "$split" = block ] && continue
      out="$work/$name-$split-$np.exr"
      start=$(date +%s.%N)
      BRDFBAKE_MPI_SPLIT=$split mpirun -q --oversubscribe -np "$np" "$exe" $args --no-preview -q -o "$out" 2> "$work/err"
      end=$(date +%s.%N)
      wall=$(echo "$end - $start" | bc -l)
      [ -z "$t1" ] && t1=$wall
      eff=$(echo "$t1 / ($np * $wall)" | bc -l)
      stats=$(grep "brdfbake: mpi:" "$work/err" || true)
      steps=$(echo "$stats" | sed -n 's/.* \([0-9]*\) steps.*/\1/p'); bytes=$(echo "$stats" | sed -n 's/.*steps, \([0-9]*\) bytes.*/\1/p')
      insteps=$(echo "$stats" | sed -n 's/.*gathered, \([0-9.]*\) s in steps.*/\1/p')
      same=yes
      cmp -s "$out" "$work/$name-cyclic-1.exr" || same=NO
      printf "| %s | %s | %d | %.2f | %.2f | %s | %s | %s | %s |\n" "$name" "$split" "$np" "$wall" "$eff" \
        "${steps:--}" "${bytes:--}" "${insteps:--}" "$same" >> "$work/record.md"
      echo "$name $split $np: $wall s" >&2
    done
  done
done
echo >> "$work/record.md"
echo "Tables: dielectric = \`${tables[dielectric]}\` (864 cells); tolerance = \`${tables[tolerance]}\` (256 cells)." >> "$work/record.md"
mkdir -p "$(dirname "$record")"
cp "$work/record.md" "$record"
cat "$record"
