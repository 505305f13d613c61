#!/usr/bin/env bash
# Runs solid_benchmark for the medium and fine meshes (or the levels given), 1 and 2 ranks, each linear solver, and writes the results as
# a CSV and a Markdown table: docs/performance-solid.csv and the "Solid assembly and Newton" section of
# docs/performance.md is made from them.
# usage: benchmarks/run_solid_benchmark.sh [repetitions] [seconds per run] [levels ...]   (levels: medium fine)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bench="$root/build/benchmarks/solid_benchmark"
repetitions=${1:-5}
limit=${2:-1500}   # seconds per configuration
shift $(( $# < 2 ? $# : 2 ))
[ $# -gt 0 ] && levels=("$@") || levels=(medium fine)
csv="$root/docs/performance-solid.csv"
mpi=(mpiexec --allow-run-as-root --oversubscribe)
header=""
rows=()
for level in "${levels[@]}"; do
  for solver in mumps gmres-ilu; do
    for ranks in 1 2; do
      echo "solid_benchmark $level $solver on $ranks rank(s)..." >&2
      if output=$(OMP_NUM_THREADS=1 timeout "$limit" "${mpi[@]}" -np "$ranks" "$bench" "$level" "$solver" "$repetitions"); then
        header=$(echo "$output" | head -n 1)
        rows+=("$(echo "$output" | tail -n 1)")
      else
        rows+=("$level,$ranks,$solver,did not finish within ${limit} s")
      fi
    done
  done
done
{ echo "$header"; printf '%s\n' "${rows[@]}"; } > "$csv"
echo "wrote $csv" >&2
