#!/usr/bin/env bash
# One command for a new user: installs the dependencies, builds, and runs the app on its embedded default scene.
# Results land in ./spatula-output (HDF5 + XDMF for ParaView, CSV and text summaries).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bash "$root/scripts/install-dependencies.sh"
bash "$root/scripts/build.sh"
"$root/build/apps/spatula/spatula" "$@"
