#!/usr/bin/env bash
# Compiles the laws and element kernels for an NVIDIA GPU with nvcc, and runs them there where a GPU is present
# (tests/device/element_kernels_on_device.cpp: the device's energies, residuals and tangents against the host's):
#
#   bash scripts/check-device-kernels.sh [--work DIR] [--arch AMPERE80]
#
# It builds Kokkos alone (Trilinos 13.2's Kokkos 3.4, from Debian's source package, as scripts/build-trilinos.sh
# fetches it) with the CUDA backend into <work>/kokkos-cuda-install-<arch>, a few minutes on one core, then the check program
# with nvcc, and prints ptxas' register, stack and spill counts for the kernel (one Kokkos per --arch). Needs nvcc (PATH or /usr/local/cuda),
# no GPU: without one it stops after linking. Kokkos 3.4 predates CUDA 12; with nvcc 13 two of its files need small
# changes, made in the copy it builds (CUDA's half type left out, cudaMemPrefetchAsync's new signature). --arch is the
# Kokkos architecture (AMPERE80 default; Kokkos 3.4 knows none newer than AMPERE86, whose code runs on newer GPUs).
# The scatter into Tpetra's matrix is not in the check: it needs a CUDA-enabled Tpetra (build-trilinos.sh --cuda).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
WORK=/opt/trilinos-build
ARCH=AMPERE80
while [ $# -gt 0 ]; do
  case "$1" in
    --work) WORK=$2; shift 2 ;;
    --arch) ARCH=$2; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) echo "check-device-kernels.sh: unknown option '$1' (allowed: --work DIR, --arch KOKKOS_ARCH)" >&2; exit 2 ;;
  esac
done
case "$ARCH" in
  TURING75|AMPERE80|AMPERE86) SM=sm_${ARCH//[!0-9]/} ;;
  *) echo "check-device-kernels.sh: --arch '$ARCH': one of TURING75, AMPERE80, AMPERE86 (CUDA 13 builds for sm_75 and newer; Kokkos 3.4 knows none newer than AMPERE86)" >&2; exit 2 ;;
esac
export PATH=$PATH:/usr/local/cuda/bin
command -v nvcc >/dev/null || { echo "check-device-kernels.sh: no nvcc on PATH or in /usr/local/cuda/bin" >&2; exit 2; }
STARTED=$(date +%s)
say() { printf '[check-device-kernels %4ds] %s\n' "$(( $(date +%s) - STARTED ))" "$*"; }
NVCC_MAJOR=$(nvcc --version | sed -n 's/.*release \([0-9]*\)\..*/\1/p')
say "nvcc $(nvcc --version | sed -n 's/.*release \([0-9.]*\),.*/\1/p'), Kokkos architecture $ARCH ($SM)"

mkdir -p "$WORK"
SOURCE=$(find "$WORK" -maxdepth 1 -type d -name 'trilinos-13.2*' | head -n 1)
if [ -z "$SOURCE" ]; then
  grep -rqs '^Types:.*deb-src\|^deb-src ' /etc/apt/sources.list /etc/apt/sources.list.d/ ||
    { echo "check-device-kernels.sh: no deb-src line: run scripts/build-trilinos.sh --configure-only once (it adds one and fetches the source)" >&2; exit 2; }
  say "fetching Debian's trilinos source package into $WORK"
  rm -rf "$WORK/source.partial" && mkdir "$WORK/source.partial"
  (cd "$WORK/source.partial" && apt-get source -qq trilinos >/dev/null)
  FETCHED=$(find "$WORK/source.partial" -maxdepth 1 -type d -name 'trilinos-13.2*' | head -n 1)
  mv "$FETCHED" "$WORK/" && rm -rf "$WORK/source.partial"
  SOURCE="$WORK/$(basename "$FETCHED")"
fi

KOKKOS="$WORK/kokkos-cuda-source" PREFIX="$WORK/kokkos-cuda-install-$ARCH" BUILD="$WORK/kokkos-cuda-build-$ARCH"
if [ ! -f "$PREFIX/lib/libkokkoscore.a" ]; then
  rm -rf "$KOKKOS" "$BUILD" && cp -r "$SOURCE/packages/kokkos" "$KOKKOS"
  # nvcc_wrapper's default architecture (sm_35, which CUDA 12 and later refuse) for CMake's compiler check.
  sed -i 's/^default_arch="sm_35"/default_arch="${NVCC_WRAPPER_DEFAULT_ARCH:-sm_35}"/' "$KOKKOS/bin/nvcc_wrapper"
  if [ "$NVCC_MAJOR" -ge 13 ]; then
    say "adapting Kokkos 3.4 to nvcc $NVCC_MAJOR (in the copy): no CUDA half type, cudaMemPrefetchAsync with a location"
    python3 - "$KOKKOS" <<'PYTHON'
import sys
root = sys.argv[1] + '/core/src/Cuda/'
def change(name, old, new):
    text = open(root + name).read()
    assert old in text, f'{name}: the text to change is not there'
    open(root + name, 'w').write(text.replace(old, new))
change('Kokkos_Cuda_Half.hpp', '      defined(KOKKOS_ARCH_MAXWELL52))\n',
       '      defined(KOKKOS_ARCH_MAXWELL52)) && \\\n    !(defined(__CUDACC_VER_MAJOR__) && __CUDACC_VER_MAJOR__ >= 13)\n')
change('Kokkos_CudaSpace.cpp',
       '    CUDA_SAFE_CALL(cudaMemPrefetchAsync(ptr, bytes, space.cuda_device(),\n'
       '                                        space.cuda_stream()));\n',
       '#if CUDA_VERSION >= 13000\n    cudaMemLocation location{};\n    location.type = cudaMemLocationTypeDevice;\n'
       '    location.id = space.cuda_device();\n'
       '    CUDA_SAFE_CALL(cudaMemPrefetchAsync(ptr, bytes, location, 0, space.cuda_stream()));\n#else\n'
       '    CUDA_SAFE_CALL(cudaMemPrefetchAsync(ptr, bytes, space.cuda_device(),\n'
       '                                        space.cuda_stream()));\n#endif\n')
PYTHON
  fi
  say "building Kokkos with CUDA into $PREFIX (log: $WORK/kokkos-cuda-build.log)"
  export NVCC_WRAPPER_DEFAULT_ARCH=$SM
  { cmake -G Ninja -S "$KOKKOS" -B "$BUILD" -DCMAKE_CXX_COMPILER="$KOKKOS/bin/nvcc_wrapper" -DCMAKE_CXX_STANDARD=17 \
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$PREFIX" -DKokkos_ENABLE_SERIAL=ON -DKokkos_ENABLE_CUDA=ON \
      -DKokkos_ENABLE_CUDA_LAMBDA=ON -DKokkos_ARCH_$ARCH=ON && ninja -C "$BUILD" install; } > "$WORK/kokkos-cuda-build.log" 2>&1 ||
    { echo "check-device-kernels.sh: the Kokkos build failed, see $WORK/kokkos-cuda-build.log" >&2; grep -m 10 'error' "$WORK/kokkos-cuda-build.log" >&2; exit 1; }
fi

say "compiling tests/device/element_kernels_on_device.cpp for $SM"
INCLUDE="$WORK/kokkos-cuda-check/include"
mkdir -p "$INCLUDE"
for package in laws elements mesh contact; do ln -sfn "$ROOT/packages/$package/src" "$INCLUDE/$package"; done
export NVCC_WRAPPER_DEFAULT_ARCH=$SM
# Compiled by Kokkos' wrapper, linked by nvcc itself (the wrapper puts libraries before the object, in front of what
# needs them).
CHECK="$WORK/kokkos-cuda-check/element_kernels_on_device"
{ "$KOKKOS/bin/nvcc_wrapper" -std=c++17 -O2 --expt-extended-lambda -Xptxas=-v -I"$INCLUDE" -I"$PREFIX/include" \
    -c "$ROOT/tests/device/element_kernels_on_device.cpp" -o "$CHECK.o" &&
  nvcc -arch="$SM" "$CHECK.o" "$PREFIX/lib/libkokkoscontainers.a" "$PREFIX/lib/libkokkoscore.a" -lcuda -ldl -o "$CHECK"
} > "$WORK/kokkos-cuda-check/compile.log" 2>&1 ||
  { echo "check-device-kernels.sh: the check did not compile, see $WORK/kokkos-cuda-check/compile.log" >&2
    grep -m 20 'error' "$WORK/kokkos-cuda-check/compile.log" >&2; exit 1; }
# The element kernel's launch: ptxas' line for the ParallelFor over main's lambda.
USAGE=$(grep -A2 'Function properties for .*ParallelFor.*mainEUli' "$WORK/kokkos-cuda-check/compile.log" | grep -E 'stack frame|registers' |
  sed 's/^ *//; s/ptxas info *: //' | paste -sd ';' - || true)
say "the element kernel on $SM: ${USAGE:-ptxas gave no line for it}"
status=0
"$CHECK" || status=$?
[ "$status" = 77 ] && exit 0   # no GPU here: compiled and linked, not run (it said so)
exit "$status"
