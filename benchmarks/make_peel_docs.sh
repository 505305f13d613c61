#!/usr/bin/env bash
# Regenerates the Q1C1 vs Q1C2 peel curves of docs/adhesion.md (Kendall's strip, 5 nm elements along it):
# docs/peel-q1c1-q1c2-90.png and -45.png, and prints the steady forces. usage: benchmarks/make_peel_docs.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$root/build/benchmarks/peel_curves" 90 110 70 32 "$work/90.csv"
/usr/bin/python3 "$root/benchmarks/plot_peel_curves.py" "$work/90.csv" 0.030618 \
  "Kendall peel at 90 deg: 5 nm strip, 5 nm elements, stiction law" "$root/docs/peel-q1c1-q1c2-90.png"
"$root/build/benchmarks/peel_curves" 45 33 20 64 "$work/45.csv"
/usr/bin/python3 "$root/benchmarks/plot_peel_curves.py" "$work/45.csv" 0.102889 \
  "Kendall peel at 45 deg: 5 nm strip, 2.5 nm elements, stiction law (Q1C1 stops: no convergence)" "$root/docs/peel-q1c1-q1c2-45.png"
