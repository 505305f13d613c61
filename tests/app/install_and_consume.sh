#!/usr/bin/env bash
# Installs the project into a scratch prefix and builds a separate CMake project against it with
# find_package(Spatula), then runs it. usage: install_and_consume.sh <build dir> <source dir>
set -eu
build=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$source_dir/tests/consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/build" -j 2 > "$work/build.log"
"$work/build/consumer"
