#!/usr/bin/env bash
# Builds Trilinos 13.2 from Debian's source package with a threaded Kokkos backend (OpenMP; with --cuda also CUDA),
# only the packages this project links, into a prefix that later builds of the project reuse:
#
#   bash scripts/build-trilinos.sh [--prefix DIR] [--work DIR] [--jobs N] [--cuda] [--explicit-instantiation]
#                                  [--configure-only] [--force]
#   cmake -S . -B build-openmp -DTrilinos_DIR=<prefix>/lib/cmake/Trilinos && cmake --build build-openmp -j2
#
# Defaults: prefix /opt/trilinos-13.2-openmp (-openmp-cuda with --cuda), work directory /opt/trilinos-build (source, build tree, ccache), all
# cores. It installs what it needs with apt-get (ninja, ccache, dpkg-dev, compilers, MPI, BLAS/LAPACK, MUMPS, HDF5),
# adds a deb-src line for bookworm main if there is none, and fetches the source with `apt-get source trilinos`
# (Debian's patches applied). A build that is stopped goes on where it stopped when the script is run again (Ninja
# and ccache keep the work); an installed prefix is left alone unless --force, which reconfigures and rebuilds from a
# fresh build tree (ccache makes the compiles cheap). Progress: a line per 2 % of the build steps with the elapsed
# time; the total time at the end, summed over the calls of a resumed build (also in <prefix>/BUILD-INFO.txt).
# Without root, pass --prefix and --work in directories you can write (e.g. under $HOME); apt-get then runs by sudo.
#
# Packages: Teuchos, Kokkos, KokkosKernels, Tpetra, Thyra, Stratimikos, NOX with LOCA, Belos, Ifpack2, MueLu and
# Amesos2 (and what they require), MPI on, shared libraries, Release, no tests or examples. Kokkos: OpenMP only (its
# node is Tpetra's default one), so the project's kernels run threaded with KOKKOS_NUM_THREADS threads per rank.
# Templates are instantiated where they are used (Trilinos_ENABLE_EXPLICIT_INSTANTIATION=OFF): the Trilinos build
# then has 764 compiles, mostly light ones, instead of 1,068 with Tpetra's, Ifpack2's and MueLu's explicit
# instantiations (some of them minutes each), and the project's compiles do the instantiating for the few classes it
# uses. --explicit-instantiation builds those libraries instead (longer here, faster project builds afterwards; its
# own prefix, suffix -eti). --cuda (nvcc on PATH, and KOKKOS_ARCH naming the GPU, e.g. KOKKOS_ARCH=AMPERE80)
# sets Kokkos_ENABLE_CUDA as well, with Kokkos' nvcc_wrapper as the compiler, into its own prefix. Trilinos 13.2
# carries Kokkos 3.4, which knows CUDA toolkits up to 11.x: a newer toolkit (this machine has CUDA 13.0 in
# /usr/local/cuda) is expected to fail, which is why CUDA is asked for, not detected.
set -euo pipefail

PREFIX=
WORK=/opt/trilinos-build
JOBS=$(nproc)
CUDA=off
INSTANTIATION=implicit
FORCE=0
CONFIGURE_ONLY=0
while [ $# -gt 0 ]; do
  case "$1" in
    --prefix) PREFIX=$2; shift 2 ;;
    --work) WORK=$2; shift 2 ;;
    --jobs) JOBS=$2; shift 2 ;;
    --cuda) CUDA=on; shift ;;
    --explicit-instantiation) INSTANTIATION=explicit; shift ;;
    --force) FORCE=1; shift ;;
    --configure-only) CONFIGURE_ONLY=1; shift ;;
    -h|--help) sed -n '2,29p' "$0"; exit 0 ;;
    *) echo "build-trilinos.sh: unknown option '$1' (allowed: --prefix DIR, --work DIR, --jobs N, --cuda, --explicit-instantiation, --force, --configure-only)" >&2
       exit 2 ;;
  esac
done
case "$JOBS" in ''|*[!0-9]*|0) echo "build-trilinos.sh: --jobs '$JOBS': expected a positive integer" >&2; exit 2 ;; esac

SUFFIX=; [ "$INSTANTIATION" = explicit ] && SUFFIX=-eti
[ "$CUDA" = on ] && PREFIX=${PREFIX:-/opt/trilinos-13.2-openmp-cuda$SUFFIX} || PREFIX=${PREFIX:-/opt/trilinos-13.2-openmp$SUFFIX}
STARTED=$(date +%s)
say() { printf '[build-trilinos %5ds] %s\n' "$(( $(date +%s) - STARTED ))" "$*"; }

if [ -f "$PREFIX/lib/cmake/Trilinos/TrilinosConfig.cmake" ] && [ "$FORCE" = 0 ]; then
  say "already installed in $PREFIX (--force rebuilds); configure the project with -DTrilinos_DIR=$PREFIX/lib/cmake/Trilinos"
  exit 0
fi

# Both directories must be writable (or creatable) before anything is installed or fetched.
for directory in "$PREFIX" "$WORK"; do
  parent=$directory; while [ ! -e "$parent" ]; do parent=$(dirname "$parent"); done
  [ -w "$parent" ] || { echo "build-trilinos.sh: cannot write '$parent' (for '$directory'): run as root or pass --prefix and --work in directories you own" >&2; exit 2; }
done

SUDO=; [ "$(id -u)" = 0 ] || SUDO=sudo
say "installing the build tools and libraries (apt-get)"
$SUDO apt-get update -qq
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq ninja-build ccache dpkg-dev cmake g++ gfortran \
  libopenmpi-dev openmpi-bin libopenblas-dev liblapack-dev libmumps-dev libhdf5-openmpi-dev >/dev/null

SOURCES=/etc/apt/sources.list.d/debian-bookworm-src.sources
if ! grep -rqs '^Types:.*deb-src\|^deb-src ' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  say "adding a deb-src line for bookworm main ($SOURCES)"
  printf 'Types: deb-src\nURIs: http://deb.debian.org/debian\nSuites: bookworm\nComponents: main\nSigned-By: %s\n' \
    /usr/share/keyrings/debian-archive-keyring.gpg | $SUDO tee "$SOURCES" >/dev/null
  $SUDO apt-get update -qq
fi

mkdir -p "$WORK"
SOURCE=$(find "$WORK" -maxdepth 1 -type d -name 'trilinos-13.2*' | head -n 1)
if [ -z "$SOURCE" ]; then
  # Fetched and unpacked in a scratch directory and moved into place only when complete: a download or unpacking
  # that was stopped is never taken for the source.
  say "fetching Debian's trilinos source package into $WORK"
  rm -rf "$WORK/source.partial" && mkdir "$WORK/source.partial"
  (cd "$WORK/source.partial" && apt-get source -qq trilinos >/dev/null)
  FETCHED=$(find "$WORK/source.partial" -maxdepth 1 -type d -name 'trilinos-13.2*' | head -n 1)
  [ -n "$FETCHED" ] || { echo "build-trilinos.sh: apt-get source trilinos gave no trilinos-13.2* directory" >&2; exit 1; }
  mv "$FETCHED" "$WORK/" && rm -rf "$WORK/source.partial"
  SOURCE="$WORK/$(basename "$FETCHED")"
fi
say "source: $SOURCE"

BACKENDS=(-DKokkos_ENABLE_SERIAL=OFF -DKokkos_ENABLE_OPENMP=ON -DTrilinos_ENABLE_OpenMP=ON
          -DTpetra_INST_SERIAL=OFF -DTpetra_INST_OPENMP=ON)
[ "$INSTANTIATION" = explicit ] && ETI=ON || ETI=OFF
COMPILER=(-DCMAKE_CXX_COMPILER=mpicxx -DCMAKE_C_COMPILER=mpicc -DCMAKE_Fortran_COMPILER=mpif90)
VARIANT=openmp
if [ "$CUDA" = on ]; then
  command -v nvcc >/dev/null || { echo "build-trilinos.sh: --cuda: no nvcc on PATH (add the CUDA toolkit's bin directory)" >&2; exit 2; }
  [ -n "${KOKKOS_ARCH:-}" ] || { echo "build-trilinos.sh: --cuda: set KOKKOS_ARCH to the GPU's Kokkos name (e.g. KOKKOS_ARCH=AMPERE80, VOLTA70)" >&2; exit 2; }
  WRAPPER="$SOURCE/packages/kokkos/bin/nvcc_wrapper"
  BACKENDS+=(-DKokkos_ENABLE_CUDA=ON -DKokkos_ENABLE_CUDA_LAMBDA=ON -DKokkos_ARCH_${KOKKOS_ARCH}=ON
             -DTpetra_INST_CUDA=ON -DTpetra_ASSUME_CUDA_AWARE_MPI=OFF)
  export OMPI_CXX=$WRAPPER
  VARIANT=openmp+cuda
fi
VARIANT=$VARIANT-$INSTANTIATION

BUILD="$WORK/build-$VARIANT"
# --force starts a fresh build tree unless the last one never got to install (a forced rebuild that was stopped, which
# then goes on).
if [ "$FORCE" = 1 ] && [ -f "$BUILD/.installed" ]; then
  say "--force: removing the build tree $BUILD (the ccache stays)"
  rm -rf "$BUILD" "$WORK/build-$VARIANT.seconds" "$WORK/build-$VARIANT.seconds.current"
fi
if [ ! -f "$BUILD/build.ninja" ]; then
  say "configuring ($VARIANT) in $BUILD"
  PACKAGES=(Teuchos Kokkos KokkosKernels Tpetra Thyra Stratimikos NOX Belos Ifpack2 MueLu Amesos2)
  cmake -G Ninja -S "$SOURCE" -B "$BUILD" -Wno-dev \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$PREFIX" -DBUILD_SHARED_LIBS=ON \
    -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache "${COMPILER[@]}" \
    -DTPL_ENABLE_MPI=ON -DTPL_ENABLE_BLAS=ON -DTPL_BLAS_LIBRARIES=openblas -DTPL_ENABLE_LAPACK=ON \
    -DTPL_LAPACK_LIBRARIES=lapack -DTPL_ENABLE_Boost=OFF -DTPL_ENABLE_Netcdf=OFF -DTPL_ENABLE_HDF5=OFF \
    -DTrilinos_ENABLE_ALL_PACKAGES=OFF -DTrilinos_ENABLE_ALL_OPTIONAL_PACKAGES=OFF \
    -DTrilinos_ENABLE_SECONDARY_TESTED_CODE=ON -DTrilinos_ENABLE_TESTS=OFF -DTrilinos_ENABLE_EXAMPLES=OFF \
    $(printf -- '-DTrilinos_ENABLE_%s=ON ' "${PACKAGES[@]}") -DNOX_ENABLE_LOCA=ON -DNOX_ENABLE_ABSTRACT_IMPLEMENTATION_THYRA=ON \
    -DMueLu_ENABLE_Tpetra=ON -DMueLu_ENABLE_Epetra=OFF -DTrilinos_ENABLE_Epetra=OFF -DTrilinos_ENABLE_EpetraExt=OFF \
    -DTrilinos_ENABLE_EXPLICIT_INSTANTIATION=$ETI -DCMAKE_INSTALL_RPATH="$PREFIX/lib" "${BACKENDS[@]}" > "$WORK/configure-$VARIANT.log" 2>&1 \
    || { echo "build-trilinos.sh: configure failed, see $WORK/configure-$VARIANT.log" >&2; tail -n 30 "$WORK/configure-$VARIANT.log" >&2; exit 1; }
fi

if [ "$CONFIGURE_ONLY" = 1 ]; then
  say "configured in $BUILD ($(grep -c '^build ' "$BUILD/build.ninja") build statements); run without --configure-only to build"
  exit 0
fi
# Paths under the work directory hashed relative to it, so a fresh build tree there hits the cache too.
export CCACHE_DIR="$WORK/ccache" CCACHE_MAXSIZE=5G CCACHE_BASEDIR="$WORK"
say "building with $JOBS jobs (log: $WORK/build-$VARIANT.log)"
# The seconds of every call, so that a build stopped and resumed reports its total: each call keeps its elapsed time
# in $SPENT.current at every progress line (a killed call thus counts to its last one), moved to $SPENT next time.
SPENT="$WORK/build-$VARIANT.seconds"
[ -f "$SPENT.current" ] && cat "$SPENT.current" >> "$SPENT" && rm -f "$SPENT.current"
set +e
NINJA_STATUS='[%f/%t] ' ninja -C "$BUILD" -j "$JOBS" install 2>&1 | tee "$WORK/build-$VARIANT.log" |
  awk -v started="$STARTED" -v spent="$SPENT.current" '
    match($0, /^\[[0-9]+\/[0-9]+\]/) {
      split(substr($0, 2, RLENGTH - 2), n, "/")
      percent = int(100 * n[1] / n[2])
      if (percent >= shown + 2) { shown = percent; printf("[build-trilinos %5ds] %3d %% (%d of %d steps)\n", systime() - started, percent, n[1], n[2]); fflush()
                                  print systime() - started > spent; close(spent) }
    }
    /error:|FAILED:/ { print; fflush() }'
STATUS=${PIPESTATUS[0]}
set -e
if [ "$STATUS" != 0 ]; then
  echo "build-trilinos.sh: the build failed (exit $STATUS), see $WORK/build-$VARIANT.log; run the script again to go on" >&2
  exit "$STATUS"
fi
rm -f "$SPENT.current"
echo $(( $(date +%s) - STARTED )) >> "$SPENT"
touch "$BUILD/.installed"
CALLS=$(wc -l < "$SPENT")
SECONDS_TAKEN=$(awk '{ total += $1 } END { print total }' "$SPENT")
printf 'Trilinos 13.2 (%s) from %s\nbuilt %s with %s jobs in %d s over %d call(s) of the script\n' \
  "$VARIANT" "$SOURCE" "$(date -u +%Y-%m-%dT%H:%MZ)" "$JOBS" "$SECONDS_TAKEN" "$CALLS" > "$PREFIX/BUILD-INFO.txt"
say "installed in $PREFIX ($VARIANT) in ${SECONDS_TAKEN} s over $CALLS call(s)"
say "configure the project with: cmake -S . -B build-openmp -DTrilinos_DIR=$PREFIX/lib/cmake/Trilinos"
