# What `make fuzz` runs: KIND=build configures and builds the fuzz sub-project (tests/fuzz,
# clang, ASan and UBSan) into the build tree; KIND template, scene, ply or cut runs that
# parser's fuzzer, built before (KIND cache: the cut cache's entry decoding), for SECONDS
# seconds: any crash, sanitizer report, timeout or out-of-memory fails. Not part of `make test`.
#   cmake -DKIND=build -DSOURCE_DIR=<repo> -DBINARY_DIR=<build>/fuzz -DCLANGXX=clang++
#         -DGENERATOR=Ninja -P tests/fuzz/run_fuzz.cmake
#   cmake -DKIND=template -DSECONDS=60 -DSOURCE_DIR=<repo> -DBINARY_DIR=<build>/fuzz ...
set(required KIND SOURCE_DIR BINARY_DIR CLANGXX GENERATOR)
if(NOT KIND STREQUAL "build")
  list(APPEND required SECONDS)
endif()
foreach(var ${required})
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_fuzz.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT EXISTS "${CLANGXX}")
  message(FATAL_ERROR "the fuzz target needs clang++ with libFuzzer (Debian 12: apt-get install "
                      "clang libclang-rt-14-dev); found: ${CLANGXX}")
endif()

if(KIND STREQUAL "build")
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/fuzz -B ${BINARY_DIR} -G ${GENERATOR}
            -DCMAKE_CXX_COMPILER=${CLANGXX} -DCMAKE_BUILD_TYPE=RelWithDebInfo
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring the fuzz target failed:\n${out}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "building the fuzz target failed:\n${out}")
  endif()
  message(STATUS "the fuzz targets are built in ${BINARY_DIR}")
  return()
endif()
if(NOT EXISTS ${BINARY_DIR}/${KIND}_fuzz)
  message(FATAL_ERROR "${BINARY_DIR}/${KIND}_fuzz is missing: KIND=build (make fuzz) builds it")
endif()

# Seed corpus: the shipped files and the bad-input fixtures of the format. The working corpus
# persists in the build tree, so coverage grows from run to run.
set(work ${BINARY_DIR}/${KIND})
file(REMOVE_RECURSE ${work}/seeds)
file(MAKE_DIRECTORY ${work}/seeds ${work}/corpus ${work}/artifacts)
if(KIND STREQUAL "ply")
  # Small PLY files only: libFuzzer's longest input follows the longest seed.
  file(GLOB seeds ${SOURCE_DIR}/tests/fuzz/ply_corpus/*.ply ${SOURCE_DIR}/tests/data/*.ply)
elseif(KIND STREQUAL "cut")
  file(GLOB seeds ${SOURCE_DIR}/tests/fuzz/cut_corpus/*)
elseif(KIND STREQUAL "cache")
  file(GLOB seeds ${SOURCE_DIR}/tests/fuzz/cache_corpus/*)
elseif(KIND STREQUAL "scene")
  file(GLOB seeds ${SOURCE_DIR}/scenes/*.yaml ${SOURCE_DIR}/tests/data/scenes/*.yaml
       ${SOURCE_DIR}/tests/data/scenes/bad/*.yaml)
else()
  file(GLOB seeds ${SOURCE_DIR}/templates/*.yaml ${SOURCE_DIR}/tests/bad_input/*)
endif()
file(COPY ${seeds} DESTINATION ${work}/seeds)
set(dict)
if(EXISTS ${SOURCE_DIR}/tests/fuzz/${KIND}.dict)
  set(dict -dict=${SOURCE_DIR}/tests/fuzz/${KIND}.dict)
endif()

execute_process(
  COMMAND ${CMAKE_COMMAND} -E env
          ASAN_OPTIONS=detect_stack_use_after_return=1:allocator_may_return_null=0
          UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
          ${BINARY_DIR}/${KIND}_fuzz -max_total_time=${SECONDS} -rss_limit_mb=2048 -timeout=10
          ${dict} -print_final_stats=1
          -artifact_prefix=${work}/artifacts/ ${work}/corpus ${work}/seeds
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
# libFuzzer prints a line per new input: keep the start (the seed run) and the end (stats).
string(LENGTH "${out}" len)
if(len GREATER 12000)
  math(EXPR tail_from "${len} - 8000")
  string(SUBSTRING "${out}" 0 3000 head)
  string(SUBSTRING "${out}" ${tail_from} -1 tail)
  set(out "${head}\n...\n${tail}")
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the ${KIND}-parser fuzzer found a problem (exit code ${rc}); the input "
                      "is in ${work}/artifacts/:\n${out}")
endif()
message(STATUS "fuzz_${KIND}_parser: no findings in ${SECONDS} s\n${out}")
