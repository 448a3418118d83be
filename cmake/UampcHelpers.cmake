# Helpers shared by every CMakeLists.txt of uampc.

# uampc_compile_in_batches(target ...)
# Compiles a target's sources in batches of up to eight (CMake's unity build): the heavy headers
# (Eigen, Fast DDS, nlohmann::json, GoogleTest) are parsed once per batch instead of once per file.
# Measured on two cores without ccache: the generated message types 125 -> 22 s of CPU, the world
# core 52 -> 30 s, the evaluator core 45 -> 23 s. Same flags, so the same results bit for bit (no
# -ffast-math, no FMA contraction in ISO C++ mode). Two costs: file-local names must differ between
# batch mates (the build fails and names both when they do not), and compile_commands.json lists the
# batches, not the files. Files with their own COMPILE_OPTIONS are compiled on their own.
# Not used for the LO core: its time is one file (iterated_ekf.cpp), batching saved 12 %.
# -DUAMPC_COMPILE_IN_BATCHES=OFF compiles every file on its own (an editor's clangd wants that).
option(UAMPC_COMPILE_IN_BATCHES "compile targets in batches of files (unity builds)" ON)
function(uampc_compile_in_batches)
  if(UAMPC_COMPILE_IN_BATCHES)
    set_target_properties(${ARGN} PROPERTIES UNITY_BUILD ON)
  endif()
endfunction()

# uampc_off_hot_path(target ...)
# Code the simulation never runs per step (the command line, scene and IDL parsing, experiments and
# reports, the tests' own code) is compiled at -O1 instead of the build type's -O3: a third less
# compile time per file (main.cpp 22 -> 14 s, run_files_test.cpp 18 -> 11 s), and a clean build on
# two cores was the slowest part of CI. Only the optimisation level changes: no -ffast-math, no FMA
# without -march, so every result is the same bit for bit. What a step runs (LO, UA-MPC, ray-caster,
# evaluator, DDS nodes, lockstep clock, generated types) keeps -O3. The flag comes after the build
# type's, and the last -O wins (also over the sanitizer presets' -O2).
# Such targets are compiled in batches too.
function(uampc_off_hot_path)
  foreach(target IN LISTS ARGN)
    target_compile_options(${target} PRIVATE -O1)
    uampc_compile_in_batches(${target})
  endforeach()
endfunction()

# uampc_add_test(NAME name SOURCES a.cpp ... [LIBS lib ...] [LABELS label ...])
# One GoogleTest executable registered with CTest. Tests live next to the code they test.
function(uampc_add_test)
  cmake_parse_arguments(T "" "NAME" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest_main)
  uampc_off_hot_path(${T_NAME})  # what a test runs per step is in the libraries it links
  set_target_properties(${T_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  add_test(NAME ${T_NAME} COMMAND ${T_NAME} WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
  set_tests_properties(${T_NAME} PROPERTIES
    ENVIRONMENT "UAMPC_SOURCE_DIR=${CMAKE_SOURCE_DIR}")
  if(T_LABELS)
    set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}")
  endif()
endfunction()

# uampc_add_benchmark(NAME name SOURCES a.cpp ... [LIBS lib ...])
# A Google Benchmark executable; benchmarks measure, they are never part of the test suite.
# Not in sanitizer builds (UAMPC_SANITIZE): their timings would mean nothing, and they cost build time.
function(uampc_add_benchmark)
  if(UAMPC_SANITIZE)
    return()
  endif()
  cmake_parse_arguments(B "" "NAME" "SOURCES;LIBS" ${ARGN})
  add_executable(${B_NAME} ${B_SOURCES})
  target_link_libraries(${B_NAME} PRIVATE ${B_LIBS} benchmark::benchmark)
  set_target_properties(${B_NAME} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bench)
endfunction()
