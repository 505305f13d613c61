# spatula_package(<name> SOURCES ... DEPENDS ...)
#   One library per package: target spatula_<name>, alias Spatula::<name>, headers in packages/<name>/src,
#   included as "<name>/header.hpp" and installed under include/spatula/<name>. DEPENDS lists the package's dependencies explicitly (PUBLIC). Without
#   SOURCES the package is header-only (an INTERFACE library).
# spatula_test(<name> SOURCES ... DEPENDS ... [RANKS n ...])
#   A GoogleTest executable run by CTest once per rank count (default 1); MPI runs use mpiexec.
include_guard(GLOBAL)

set(SPATULA_EXPORTED_TARGETS "" CACHE INTERNAL "")

function(spatula_package name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS" ${ARGN})
  set(target spatula_${name})
  if(ARG_SOURCES)
    set(scope PUBLIC)
    add_library(${target} ${ARG_SOURCES})
    target_compile_options(${target} PRIVATE -Wall -Wextra)
    set_target_properties(${target} PROPERTIES OUTPUT_NAME spatula_${name})
  else()   # header-only package (laws and element kernels)
    set(scope INTERFACE)
    add_library(${target} INTERFACE)
  endif()
  add_library(Spatula::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  # Headers are included with their package's name ("laws/lennard_jones.hpp"): in the build tree include/<name> is
  # a link to the package's src/, in the install tree the headers are in include/spatula/<name>/.
  file(MAKE_DIRECTORY ${PROJECT_BINARY_DIR}/include)
  file(CREATE_LINK ${CMAKE_CURRENT_SOURCE_DIR}/src ${PROJECT_BINARY_DIR}/include/${name} SYMBOLIC)
  target_include_directories(${target} ${scope}
    $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/spatula>)
  target_link_libraries(${target} ${scope} ${ARG_DEPENDS})
  file(GLOB headers ${CMAKE_CURRENT_SOURCE_DIR}/src/*.hpp)
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/spatula/${name})
  install(TARGETS ${target} EXPORT SpatulaTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
endfunction()

function(spatula_test name)
  if(NOT SPATULA_ENABLE_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPENDS;RANKS;LABELS" ${ARGN})
  if(NOT ARG_RANKS)
    set(ARG_RANKS 1)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} spatula_test_main GTest::gtest)
  target_compile_options(${name} PRIVATE -Wall -Wextra)
  foreach(ranks IN LISTS ARG_RANKS)
    if(ranks EQUAL 1)
      add_test(NAME ${name} COMMAND ${name})
      set(test_name ${name})
    else()
      set(test_name ${name}_np${ranks})
      add_test(NAME ${test_name} COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ranks}
               ${SPATULA_MPIEXEC_FLAGS} $<TARGET_FILE:${name}>)
    endif()
    math(EXPR processors "${ranks} * ${SPATULA_TEST_KOKKOS_THREADS}")   # cores the test keeps busy
    set_tests_properties(${test_name} PROPERTIES PROCESSORS ${processors}
      ENVIRONMENT "OMPI_MCA_rmaps_base_oversubscribe=1;OMP_NUM_THREADS=1;OMP_PROC_BIND=false;KOKKOS_NUM_THREADS=${SPATULA_TEST_KOKKOS_THREADS}")
    if(ARG_LABELS)
      set_tests_properties(${test_name} PROPERTIES LABELS "${ARG_LABELS}")
    endif()
  endforeach()
endfunction()

# mpiexec as root needs an explicit opt-in with Open MPI; harmless otherwise.
set(SPATULA_MPIEXEC_FLAGS --allow-run-as-root --oversubscribe CACHE STRING "Extra flags for mpiexec in tests")
