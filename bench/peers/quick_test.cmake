# ctest bench_peers_quick: runs `bench_peers --rounds 1 --quick` (BENCH_PEERS: its path) and
# checks that it exits 0 and prints a stiction row for every problem. Not a timing test.
execute_process(COMMAND "${BENCH_PEERS}" --rounds 1 --quick
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT code EQUAL 0)
  message(FATAL_ERROR "bench_peers exited with ${code}")
endif()
foreach(problem sphere slope_hold slope_slide)
  if(NOT out MATCHES "\\| stiction \\| rk4 \\| 1e-4 s \\| ${problem} \\| [^|]*[0-9]")
    message(FATAL_ERROR "no stiction rk4 row with an error for ${problem}")
  endif()
endforeach()
