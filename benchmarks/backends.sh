#!/usr/bin/env bash
# Kokkos backends against MPI ranks, in one run on a quiet machine: the project built against
# Debian's Serial Trilinos (build/) and against the OpenMP Trilinos of scripts/build-trilinos.sh (build-openmp/), in
# four configurations: Serial 1 rank, Serial 2 ranks, OpenMP 1 rank with 1 thread, OpenMP 1 rank with 2 threads.
#
#   bash benchmarks/backends.sh [--serial-build DIR] [--openmp-build DIR] [--levels "medium fine"] [--repetitions N]
#                               [--whole-runs N] [--whole-run-levels "medium"] [--whole-runs-only] [--csv FILE]
#
# For each level it runs
#   scatter_benchmark (the bulk solid's assembly, atomics against colouring; 1 rank): elements/s each way;
#   solid_benchmark mumps (the whole system's assembly, residual and tangent, and a Newton step of a 2.5 deg rotation):
#     elements/s and the Newton iteration split into assembly and linear solve;
# and whole runs on each of --whole-run-levels (default medium): the default scene (Q1C2 frictionless rotation) on that
# mesh to 20 deg, wall seconds, --whole-runs times per configuration (default 3), the configurations taken in turn, and
# the median recorded (single whole runs here vary by up to 32 % from one to the next). --whole-runs-only skips the
# benchmarks. Kokkos' threads are KOKKOS_NUM_THREADS and OMP_NUM_THREADS (equal, so that Kokkos does not warn of
# oversubscription); BLAS stays on one thread (OPENBLAS_NUM_THREADS=1; Debian's MUMPS has no OpenMP). Writes
# docs/backends.csv (one row per level, configuration and measurement; --csv another file) and prints it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
serial="$root/build" openmp="$root/build-openmp" levels="medium fine" repetitions=5 whole_runs=3
whole_levels=medium kernels=1 csv="$root/docs/backends.csv"
while [ $# -gt 0 ]; do
  case "$1" in
    --serial-build) serial=$(cd "$2" && pwd); shift 2 ;;
    --openmp-build) openmp=$(cd "$2" && pwd); shift 2 ;;
    --levels) levels=$2; shift 2 ;;
    --repetitions) repetitions=$2; shift 2 ;;
    --whole-runs) whole_runs=$2; shift 2 ;;
    --whole-run-levels) whole_levels=$2; shift 2 ;;
    --whole-runs-only) kernels=0; shift ;;
    --csv) csv=$(cd "$(dirname "$2")" && pwd)/$(basename "$2"); shift 2 ;;
    -h|--help) sed -n '2,18p' "$0"; exit 0 ;;
    *) echo "backends.sh: unknown option '$1' (allowed: --serial-build DIR, --openmp-build DIR, --levels LIST, --repetitions N, --whole-runs N, --whole-run-levels LIST, --whole-runs-only, --csv FILE)" >&2; exit 2 ;;
  esac
done
for build in "$serial" "$openmp"; do
  for program in benchmarks/scatter_benchmark benchmarks/solid_benchmark apps/spatula/spatula; do
    [ -x "$build/$program" ] || { echo "backends.sh: $build/$program is missing (build the project there first)" >&2; exit 2; }
  done
done
header=$(sed -n 's/^SPATULA_KOKKOS_CONFIG_HEADER:FILEPATH=//p' "$openmp/CMakeCache.txt")
grep -qs '^#define KOKKOS_ENABLE_OPENMP' "$header" ||
  { echo "backends.sh: $openmp is not built against a Kokkos with OpenMP" >&2; exit 2; }

export OPENBLAS_NUM_THREADS=1 OMP_PROC_BIND=false
mpi=(mpiexec --allow-run-as-root --oversubscribe --bind-to none)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "level,configuration,measurement,value" > "$work/backends.csv"
record() { echo "$1,$2,$3,$4" >> "$work/backends.csv"; echo "$1,$2,$3,$4"; }
# configuration name, build, ranks, Kokkos threads
configurations=("Serial 1 rank|$serial|1|1" "Serial 2 ranks|$serial|2|1" "OpenMP 1 thread|$openmp|1|1"
                "OpenMP 2 threads|$openmp|1|2")
# A column of the last row of the CSV a program printed (from its header line, which starts with "level,"; Kokkos or
# MPI may print before it).
column() { python3 -c '
import csv, sys
lines = sys.stdin.read().splitlines()
header = max(i for i, line in enumerate(lines) if line.startswith(("level,", "step,")))
print(list(csv.DictReader(lines[header:]))[-1][sys.argv[1]])' "$1"; }
threaded() { KOKKOS_NUM_THREADS=$1 OMP_NUM_THREADS=$1 "${@:2}"; }

[ "$kernels" = 1 ] || levels=""
for level in $levels; do
  for configuration in "${configurations[@]}"; do
    IFS='|' read -r name build ranks threads <<< "$configuration"
    [ "$ranks" = 1 ] || continue
    out=$(threaded "$threads" "$build/benchmarks/scatter_benchmark" "$level" "$repetitions")
    record "$level" "$name" "scatter atomic elements/s" "$(echo "$out" | column atomic_elements_per_s)"
    record "$level" "$name" "scatter coloured elements/s" "$(echo "$out" | column coloured_elements_per_s)"
    record "$level" "$name" "scatter matrices' relative difference" "$(echo "$out" | column relative_matrix_difference)"
  done
  for configuration in "${configurations[@]}"; do
    IFS='|' read -r name build ranks threads <<< "$configuration"
    out=$(threaded "$threads" "${mpi[@]}" -np "$ranks" "$build/benchmarks/solid_benchmark" "$level" mumps "$repetitions")
    for key in residual_elements_per_s tangent_elements_per_s newton_s_per_iteration assembly_s_per_iteration \
               linear_s_per_iteration; do
      record "$level" "$name" "solid $key" "$(echo "$out" | column $key)"
    done
  done
done

# Whole runs: the default scene on each level's mesh to 20 deg, the configurations in turn, --whole-runs rounds. Besides
# the wall time, the run's own phase timers (rank 0): assembly (bulk and contact, residual and tangent) and the linear
# solver (MUMPS analysis, factorizations, solves), so that the solver's share is read from the same runs.
timer_sum() {   # the seconds of the timers whose names start with $1, summed, from a run's log
  awk -v prefix="spatula: $1" 'index($0, prefix) == 1 && match($0, /  [0-9.e+-]+ \(/) { total += substr($0, RSTART, RLENGTH - 2) }
                                END { printf "%.3f\n", total }' "$2"; }
median() { sort -g | awk '{ value[NR] = $1 } END { print (NR % 2) ? value[(NR + 1) / 2] : (value[NR / 2] + value[NR / 2 + 1]) / 2 }'; }
for level in $whole_levels; do
  sed -e "s#value=\"coarse\"#value=\"$level\"#" -e 's#name="theta_y" type="double" value="90"#name="theta_y" type="double" value="20"#' \
      -e 's#value="spatula-output"#value="whole-run"#' "$root/xml/default.xml" > "$work/whole-run.xml"
  rm -f "$work"/whole-*.txt
  for round in $(seq "$whole_runs"); do
    for index in "${!configurations[@]}"; do
      IFS='|' read -r name build ranks threads <<< "${configurations[$index]}"
      rm -rf "$work/whole-run"
      start=$(date +%s.%N)
      (cd "$work" && threaded "$threads" "${mpi[@]}" -np "$ranks" "$build/apps/spatula/spatula" whole-run.xml > whole-run.log 2>&1) ||
        { echo "backends.sh: the whole run failed ($level, $name), see:" >&2; tail -5 "$work/whole-run.log" >&2; exit 1; }
      wall=$(python3 -c "import sys; print(round(float(sys.argv[2]) - float(sys.argv[1]), 2))" "$start" "$(date +%s.%N)")
      echo "$wall $(timer_sum assembly "$work/whole-run.log") $(timer_sum 'linear solve' "$work/whole-run.log")" >> "$work/whole-$index.txt"
      echo "$level, round $round, $name: $wall s wall"
      moment[$index]=$(column M_y_nNnm < "$work/whole-run/curve.csv")
    done
  done
  for index in "${!configurations[@]}"; do
    IFS='|' read -r name build ranks threads <<< "${configurations[$index]}"
    record "$level" "$name" "whole run to 20 deg, median wall s of $whole_runs" "$(cut -d' ' -f1 "$work/whole-$index.txt" | median)"
    record "$level" "$name" "whole run to 20 deg, wall s of each run" "$(cut -d' ' -f1 "$work/whole-$index.txt" | paste -sd' ')"
    record "$level" "$name" "whole run to 20 deg, median assembly s" "$(cut -d' ' -f2 "$work/whole-$index.txt" | median)"
    record "$level" "$name" "whole run to 20 deg, median linear solver s" "$(cut -d' ' -f3 "$work/whole-$index.txt" | median)"
    record "$level" "$name" "whole run to 20 deg, M_y at the end (nN nm)" "${moment[$index]}"
  done
done
cp "$work/backends.csv" "$csv"
echo "backends.sh: wrote $csv"
