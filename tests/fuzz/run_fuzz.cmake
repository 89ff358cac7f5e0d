# Configures and builds the fuzz sub-project (tests/fuzz, clang) into the build tree, then runs
# the template-parser fuzzer for a bounded time; any crash, sanitizer report, timeout or
# out-of-memory fails. Run by the CTest test fuzz_template_parser:
#   cmake -DSOURCE_DIR=<repo> -DBINARY_DIR=<build>/fuzz -DCLANGXX=clang++ -DSECONDS=60
#         -DGENERATOR=Ninja -P tests/fuzz/run_fuzz.cmake
foreach(var SOURCE_DIR BINARY_DIR CLANGXX SECONDS GENERATOR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_fuzz.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT EXISTS "${CLANGXX}")
  message(FATAL_ERROR "the fuzz target needs clang++ with libFuzzer (Debian 12: apt-get install "
                      "clang libclang-rt-14-dev); found: ${CLANGXX}")
endif()

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

# Seed corpus: the shipped templates and the bad-input fixtures. The working corpus persists
# in the build tree, so coverage grows from run to run.
file(REMOVE_RECURSE ${BINARY_DIR}/seeds)
file(MAKE_DIRECTORY ${BINARY_DIR}/seeds ${BINARY_DIR}/corpus ${BINARY_DIR}/artifacts)
file(GLOB seeds ${SOURCE_DIR}/templates/*.yaml ${SOURCE_DIR}/tests/bad_input/*)
file(COPY ${seeds} DESTINATION ${BINARY_DIR}/seeds)

execute_process(
  COMMAND ${CMAKE_COMMAND} -E env
          ASAN_OPTIONS=detect_stack_use_after_return=1:allocator_may_return_null=0
          UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
          ${BINARY_DIR}/template_fuzz -max_total_time=${SECONDS} -rss_limit_mb=2048 -timeout=10
          -dict=${SOURCE_DIR}/tests/fuzz/template.dict -print_final_stats=1
          -artifact_prefix=${BINARY_DIR}/artifacts/ ${BINARY_DIR}/corpus ${BINARY_DIR}/seeds
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
  message(FATAL_ERROR "the template-parser fuzzer found a problem (exit code ${rc}); the input "
                      "is in ${BINARY_DIR}/artifacts/:\n${out}")
endif()
message(STATUS "fuzz_template_parser: no findings in ${SECONDS} s\n${out}")
