# parallax_module(NAME PRIVATE_LIBS <third-party targets> [NARROW_ISA])
# Builds src/parallax/NAME/*.cpp (except *_test.cpp) into parallax_NAME, linked to the modules
# NAME may use (PARALLAX_USES_NAME in cmake/ModuleGraph.cmake, the one place the graph is
# written), and every
# NAME/*_test.cpp into one GoogleTest executable parallax_NAME_test registered with CTest.
# NARROW_ISA registers the tests a second time (prefix "isa-sse4.2/") with Embree forced to its
# SSE4.2 kernels, as a CPU without AVX-512 runs them: without native 16-wide kernels Embree
# traces packets differently, and an AVX-512 machine would hide bugs there. Not under the
# sanitizers: the copies exercise Embree's kernels (not instrumented) through the same calls of
# ours, and the Release suites of both Debian releases run them (CI time, .ci/run).
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
    target_compile_definitions(parallax_${name}_test PRIVATE
      PARALLAX_DATA_DIR="${PARALLAX_DATA_DIR}" PARALLAX_SOURCE_DIR="${PARALLAX_SOURCE_DIR}")
    gtest_discover_tests(parallax_${name}_test DISCOVERY_TIMEOUT 60
      PROPERTIES ENVIRONMENT "PARALLAX_DATA_DIR=${PARALLAX_DATA_DIR}")
    if(PM_NARROW_ISA AND NOT PARALLAX_SANITIZE)
      gtest_discover_tests(parallax_${name}_test DISCOVERY_TIMEOUT 60 TEST_PREFIX "isa-sse4.2/"
        PROPERTIES ENVIRONMENT
          "PARALLAX_DATA_DIR=${PARALLAX_DATA_DIR};PARALLAX_EMBREE_CONFIG=isa=sse4.2")
    endif()
  endif()
endfunction()
