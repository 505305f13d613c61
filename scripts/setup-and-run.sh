#!/usr/bin/env bash
# One command for a new user: installs the dependencies, builds, and runs the app on its embedded default scene
# (the coarse spatula peeled by rotation to 90 deg, a few minutes). Results land in ./spatula-output: curve.csv
# and curve.png (moment and energies against theta_y), HDF5 + XDMF fields for ParaView, the scene and mesh summary.
# Arguments go to the app (e.g. a scene file).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-dependencies.sh"
bash "$root/scripts/build.sh"
"$root/build/apps/spatula/spatula" "$@"
scene=$root/xml/default.xml
if [ $# -gt 0 ] && [ -f "$1" ]; then scene=$1; fi
directory=$(sed -n 's|.*name="directory" type="string" value="\([^"]*\)".*|\1|p' "$scene" | head -1)
directory=${directory:-spatula-output}
if [ -f "$directory/curve.csv" ]; then /usr/bin/python3 "$root/scripts/plot_curve.py" "$directory"; fi
