# parallax_module(NAME PRIVATE_LIBS <third-party targets> [NARROW_ISA])
# Builds src/parallax/NAME/*.cpp (except *_test.cpp) into parallax_NAME, linked to the modules
# NAME may use (PARALLAX_USES_NAME in cmake/ModuleGraph.cmake, the one place the graph is
# written), and every
# NAME/*_test.cpp into one GoogleTest executable parallax_NAME_test registered with CTest.
# NARROW_ISA registers the tests a second time (prefix "isa-sse4.2/") with Embree forced to its
# SSE4.2 kernels, as a CPU without AVX-512 runs them: without native 16-wide kernels Embree
# traces packets differently, and an AVX-512 machine would hide bugs there. Only with
# PARALLAX_NARROW_ISA_TESTS (CMakeLists.txt: this machine's Release suite) and not under the
# sanitizers: the copies exercise Embree's kernels (not instrumented) through the same calls of
# ours.
# Compile settings (docs/install.md, "Compile time"; measured with tools/compile-times). A test's
# own code is glue around the library it checks, which keeps the build's optimisation; at -O3 most
# of a test file's time went to optimising GoogleTest's macros, so the tests are compiled at -Og
# (optimised as far as debugging allows; -O1 makes GCC 12 warn falsely about std::string). The
# front ends' own code (options, bindings) runs once per command and is compiled the same way.
# The tests share one precompiled GoogleTest and standard library (parallax_test_pch below),
# parsed once instead of in each of 100 files. A Debug build keeps its -O0 everywhere.
set(PARALLAX_GLUE_OPTIMIZATION $<$<NOT:$<CONFIG:Debug>>:-Og>)
set(PARALLAX_SMALL_DOCUMENT_OPTIMIZATION $<$<NOT:$<CONFIG:Debug>>:-O1>)

# Everything a module's test executable is compiled with: the same for all of them and for the
# precompiled header they share.
function(parallax_test_compile_settings target)
  target_compile_definitions(${target} PRIVATE
    PARALLAX_DATA_DIR="${PARALLAX_DATA_DIR}" PARALLAX_SOURCE_DIR="${PARALLAX_SOURCE_DIR}")
  target_compile_options(${target} PRIVATE ${PARALLAX_GLUE_OPTIMIZATION})
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 4)
  if(NOT target STREQUAL "parallax_test_pch")
    target_precompile_headers(${target} REUSE_FROM parallax_test_pch)
  endif()
endfunction()

if(BUILD_TESTING)
  # The precompiled header every test reuses. Its flags must be the tests' own (GCC refuses a
  # header compiled with others, and CMake's -Winvalid-pch with -Werror makes that an error, not
  # a silently slower build): an executable as the tests are (-fPIE, not a library's -fPIC),
  # built and never run.
  file(CONFIGURE OUTPUT "${CMAKE_BINARY_DIR}/parallax_test_pch.cpp" CONTENT "")
  add_executable(parallax_test_pch "${CMAKE_BINARY_DIR}/parallax_test_pch.cpp")
  target_link_libraries(parallax_test_pch PRIVATE GTest::gtest GTest::gtest_main)
  parallax_test_compile_settings(parallax_test_pch)
  target_precompile_headers(parallax_test_pch PRIVATE
    <gtest/gtest.h> <algorithm> <cmath> <cstdint> <cstdio> <cstring> <filesystem> <fstream>
    <functional> <map> <memory> <set> <sstream> <stdexcept> <string> <vector>)
endif()

function(parallax_module name)
  cmake_parse_arguments(PM "NARROW_ISA" "" "PRIVATE_LIBS;TEST_LIBS" ${ARGN})
  if(NOT DEFINED PARALLAX_USES_${name})
    message(FATAL_ERROR "module ${name} is not in cmake/ModuleGraph.cmake")
  endif()
  set(PM_DEPS ${PARALLAX_USES_${name}})
  file(GLOB sources CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*.cpp")
  file(GLOB tests CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/*_test.cpp")
  list(REMOVE_ITEM sources ${tests} "${CMAKE_CURRENT_SOURCE_DIR}/main.cpp")
  set(dep_targets "")
  foreach(dep ${PM_DEPS})
    list(APPEND dep_targets parallax_${dep})
  endforeach()
  if(NOT sources)  # a module of headers only (or one not yet written)
    add_library(parallax_${name} INTERFACE)
    target_include_directories(parallax_${name} INTERFACE "${CMAKE_SOURCE_DIR}/src")
    target_link_libraries(parallax_${name} INTERFACE ${dep_targets})
    return()
  endif()
  add_library(parallax_${name} STATIC ${sources})
  target_include_directories(parallax_${name} PUBLIC "${CMAKE_SOURCE_DIR}/src")
  target_link_libraries(parallax_${name} PUBLIC ${dep_targets} PRIVATE ${PM_PRIVATE_LIBS})
  target_compile_definitions(parallax_${name} PRIVATE
    PARALLAX_VERSION="${PROJECT_VERSION}")
  if(tests AND BUILD_TESTING)
    add_executable(parallax_${name}_test ${tests})
    target_link_libraries(parallax_${name}_test PRIVATE parallax_${name} ${PM_PRIVATE_LIBS}
      ${PM_TEST_LIBS} GTest::gtest GTest::gtest_main)
    parallax_test_compile_settings(parallax_${name}_test)
    gtest_discover_tests(parallax_${name}_test DISCOVERY_TIMEOUT 60
      PROPERTIES ENVIRONMENT "PARALLAX_DATA_DIR=${PARALLAX_DATA_DIR}")
    if(PM_NARROW_ISA AND PARALLAX_NARROW_ISA_TESTS AND NOT PARALLAX_SANITIZE)
      gtest_discover_tests(parallax_${name}_test DISCOVERY_TIMEOUT 60 TEST_PREFIX "isa-sse4.2/"
        PROPERTIES ENVIRONMENT
          "PARALLAX_DATA_DIR=${PARALLAX_DATA_DIR};PARALLAX_EMBREE_CONFIG=isa=sse4.2")
    endif()
  endif()
endfunction()
