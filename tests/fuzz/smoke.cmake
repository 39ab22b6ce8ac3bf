# A short, reproducible fuzz run for ctest: RUNS executions starting from the
# seed corpus, fixed random seed, new inputs kept apart from the seeds.
# cmake -DFUZZER=exe -DSEEDS=dir -DWORK=dir -DRUNS=n -DMAX_LEN=bytes [-DDICT=file] [-DOPTION=-flag=value] -P smoke.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/corpus ${WORK}/artifacts)
file(GLOB seeds ${SEEDS}/*)
if(NOT seeds)
  message(FATAL_ERROR "no seeds in ${SEEDS}: build the fuzz_*_seeds targets first (cmake --build)")
endif()
set(args -runs=${RUNS} -seed=1 -max_len=${MAX_LEN} -timeout=10 -rss_limit_mb=2048
    -artifact_prefix=${WORK}/artifacts/ -print_final_stats=1)
if(DICT)
  list(APPEND args -dict=${DICT})
endif()
if(OPTION)
  list(APPEND args ${OPTION})
endif()
execute_process(COMMAND ${FUZZER} ${args} ${WORK}/corpus ${SEEDS} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(GLOB found ${WORK}/artifacts/*)
  message(FATAL_ERROR "${FUZZER} exited with ${rc}; reproducers: ${found}\n"
    "Rerun one with: ${FUZZER} <file> (docs/fuzzing.md)")
endif()
