#!/usr/bin/env bash
# Configures and builds the project in ./build (Release). Shared by the two set-up commands.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release
cmake --build "$root/build" -j "$(nproc)"
