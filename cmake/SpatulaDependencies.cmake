# Finds the project's dependencies and exposes each as an imported target, so packages name what they use:
#   Spatula::Teuchos, Spatula::Kokkos, Spatula::Tpetra, Spatula::Solvers (NOX/Thyra/Stratimikos/Belos/Ifpack2/MueLu),
#   MPI::MPI_CXX, Spatula::HDF5, GTest::gtest_main.
# Debian's Trilinos 13.2 exports no CMake targets, only <Package>_LIBRARIES / _INCLUDE_DIRS lists.
include_guard(GLOBAL)

find_package(MPI REQUIRED COMPONENTS C CXX)

set(HDF5_PREFER_PARALLEL ON)
find_package(HDF5 REQUIRED COMPONENTS C)
if(NOT HDF5_IS_PARALLEL)
  message(WARNING "HDF5 found at ${HDF5_INCLUDE_DIRS} is not the parallel (OpenMPI) build")
endif()
if(NOT TARGET Spatula::HDF5)
  add_library(Spatula::HDF5 INTERFACE IMPORTED GLOBAL)
  set_target_properties(Spatula::HDF5 PROPERTIES
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${HDF5_C_INCLUDE_DIRS}"
    INTERFACE_INCLUDE_DIRECTORIES "${HDF5_C_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${HDF5_C_LIBRARIES};MPI::MPI_C")
endif()

set(SPATULA_TRILINOS_PACKAGES Teuchos Kokkos Tpetra Thyra Stratimikos NOX Belos Ifpack2 MueLu)
find_package(Trilinos 13.2 REQUIRED COMPONENTS ${SPATULA_TRILINOS_PACKAGES})

# One imported target per Trilinos package, from that package's own library lists.
function(spatula_trilinos_target target)
  if(TARGET Spatula::${target})
    return()
  endif()
  set(libraries)
  set(includes)
  foreach(package IN LISTS ARGN)
    list(APPEND libraries ${${package}_LIBRARIES} ${${package}_TPL_LIBRARIES})
    list(APPEND includes ${${package}_INCLUDE_DIRS} ${${package}_TPL_INCLUDE_DIRS})
  endforeach()
  list(REMOVE_DUPLICATES includes)
  add_library(Spatula::${target} INTERFACE IMPORTED GLOBAL)
  set_target_properties(Spatula::${target} PROPERTIES
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${includes}"
    INTERFACE_INCLUDE_DIRECTORIES "${includes}"
    INTERFACE_LINK_LIBRARIES "${libraries};MPI::MPI_CXX")
endfunction()

spatula_trilinos_target(Teuchos Teuchos)
spatula_trilinos_target(Kokkos Kokkos Teuchos)
spatula_trilinos_target(Tpetra Tpetra Kokkos Teuchos)
spatula_trilinos_target(Solvers NOX Stratimikos Belos Ifpack2 MueLu Thyra Tpetra Kokkos Teuchos)

# A Trilinos built with Kokkos' OpenMP backend (scripts/build-trilinos.sh) needs -fopenmp on every file that includes
# Kokkos: read the backend from Kokkos' own configuration header (Debian's Trilinos is Serial only).
# Looked up at every configure (not cached): a build directory reconfigured against another Trilinos_DIR must not keep
# the first one's header.
unset(SPATULA_KOKKOS_CONFIG_HEADER CACHE)
find_file(SPATULA_KOKKOS_CONFIG_HEADER KokkosCore_config.h PATHS ${Kokkos_INCLUDE_DIRS} NO_DEFAULT_PATH)
if(SPATULA_KOKKOS_CONFIG_HEADER)
  file(STRINGS "${SPATULA_KOKKOS_CONFIG_HEADER}" SPATULA_KOKKOS_OPENMP REGEX "^#define KOKKOS_ENABLE_OPENMP")
  if(SPATULA_KOKKOS_OPENMP)
    find_package(OpenMP REQUIRED COMPONENTS CXX)
    foreach(target Kokkos Tpetra Solvers)
      set_property(TARGET Spatula::${target} APPEND PROPERTY INTERFACE_LINK_LIBRARIES OpenMP::OpenMP_CXX)
    endforeach()
    message(STATUS "Kokkos backend: OpenMP (threads per rank: KOKKOS_NUM_THREADS, else OMP_NUM_THREADS)")
  else()
    message(STATUS "Kokkos backend: Serial")
  endif()
endif()
# Kokkos threads per rank in the unit tests (OMP_NUM_THREADS stays 1 there for OpenBLAS and MUMPS): 2 where the
# backend is threaded, so the kernels' atomics and reductions are exercised.
# Follows the backend at every configure unless given on the command line (-DSPATULA_TEST_KOKKOS_THREADS_OVERRIDE=n).
if(SPATULA_TEST_KOKKOS_THREADS_OVERRIDE)
  set(SPATULA_TEST_KOKKOS_THREADS ${SPATULA_TEST_KOKKOS_THREADS_OVERRIDE})
elseif(SPATULA_KOKKOS_OPENMP)
  set(SPATULA_TEST_KOKKOS_THREADS 2)
else()
  set(SPATULA_TEST_KOKKOS_THREADS 1)
endif()

# MUMPS (distributed direct solver): Trilinos links it as a TPL; the headers are plain Debian ones. Double-precision
# factors (dmumps) and, for 'Linear Solver/MUMPS/factor precision' = single, single-precision ones (smumps).
find_path(MUMPS_INCLUDE_DIR dmumps_c.h)
find_library(MUMPS_LIBRARY dmumps)
find_library(MUMPS_SINGLE_LIBRARY smumps)
find_library(MUMPS_COMMON_LIBRARY mumps_common)
if(MUMPS_INCLUDE_DIR AND MUMPS_LIBRARY AND MUMPS_SINGLE_LIBRARY AND NOT TARGET Spatula::MUMPS)
  add_library(Spatula::MUMPS INTERFACE IMPORTED GLOBAL)
  set_target_properties(Spatula::MUMPS PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${MUMPS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${MUMPS_LIBRARY};${MUMPS_SINGLE_LIBRARY};${MUMPS_COMMON_LIBRARY};MPI::MPI_C")
endif()

if(SPATULA_ENABLE_TESTS)
  find_package(GTest REQUIRED)
endif()
