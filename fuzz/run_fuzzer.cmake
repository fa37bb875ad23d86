# Runs one fuzz target for a bounded time (the ctest tests of fuzz/CMakeLists.txt):
#   cmake -DFUZZER=<exe> -DWORK=<folder> -DSEEDS=<glob|glob...> -DSECONDS=<n> [-DSEED=<n>] [-DRUNS=<n>]
#         [-DPAIR=<ext>] -P run_fuzzer.cmake
# SEED is libFuzzer's -seed (0 or unset: random), RUNS its -runs (unset: -1, until SECONDS have passed).
# The seeds are copied into WORK/corpus, emptied first, so the inputs libFuzzer adds never reach the repository's
# corpus. With PAIR, a seed with a sibling file of extension PAIR becomes one input: the seed, a line "#.ele",
# the sibling (the TetGen target's .node + .ele). Fails on a finding; libFuzzer saves the input in WORK as
# crash-*, leak-*, timeout-*, oom-* or slow-unit-*.

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}/corpus")
string(REPLACE "|" ";" globs "${SEEDS}")
set(count 0)
foreach(glob IN LISTS globs)
  file(GLOB files "${glob}")
  foreach(file IN LISTS files)
    get_filename_component(name "${file}" NAME)
    get_filename_component(dir "${file}" DIRECTORY)
    get_filename_component(dir_name "${dir}" NAME)
    set(copy "${WORK}/corpus/${dir_name}_${name}")
    if(PAIR)
      get_filename_component(stem "${file}" NAME_WLE)
      if(EXISTS "${dir}/${stem}${PAIR}")
        file(READ "${file}" first)
        file(READ "${dir}/${stem}${PAIR}" second)
        file(WRITE "${copy}" "${first}\n#.ele\n${second}")
      else()
        file(COPY_FILE "${file}" "${copy}")
      endif()
    else()
      file(COPY_FILE "${file}" "${copy}")
    endif()
    math(EXPR count "${count} + 1")
  endforeach()
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "no seed files match ${SEEDS}")
endif()
if(NOT DEFINED SEED OR SEED STREQUAL "")
  set(SEED 0)
endif()
if(NOT DEFINED RUNS OR RUNS STREQUAL "")
  set(RUNS -1)
endif()
message(STATUS "${FUZZER}: ${count} seeds, seed ${SEED}, ${RUNS} runs, at most ${SECONDS} s")

# -malloc_limit_mb: a single allocation above 512 MiB from an input of a few KiB means a declared size was
# trusted; -timeout: 10 s on one input is a hang.
execute_process(COMMAND "${FUZZER}" "-seed=${SEED}" "-runs=${RUNS}" "-max_total_time=${SECONDS}" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512
                        -print_final_stats=1 "-artifact_prefix=${WORK}/" "${WORK}/corpus"
                RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  file(GLOB findings "${WORK}/crash-*" "${WORK}/leak-*" "${WORK}/timeout-*" "${WORK}/oom-*" "${WORK}/slow-unit-*")
  message(FATAL_ERROR "${FUZZER} exited with ${result}; inputs: ${findings}")
endif()
