# ctest bench_peers_quick: runs `bench_peers --rounds 1 --quick` (BENCH_PEERS: its path) and
# checks that it exits 0 and prints a stiction row with a number for every problem: the one-body
# problems, the N spheres at N = 1 and 10, the pendulum, the ramp grid and the pinch (one
# point each). Not a timing test.
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
# N spheres: CPU at N = 1 and 10, the exponent, then each N's largest stick time error.
set(n "[0-9.e+-]+")
if(NOT out MATCHES "\\| stiction \\| rk4 \\| 1e-4 s \\| ${n} \\| ${n} \\| ${n} \\| ${n} \\| ${n} \\|")
  message(FATAL_ERROR "no stiction rk4 row with costs and errors for the N spheres")
endif()
if(NOT out MATCHES "Pendulum with joint friction: reference [^\n]* turns [1-9]")
  message(FATAL_ERROR "no pendulum reference")
endif()
# The hold benchmark: the ramp grid's creep, median creep and breakaway error; the pinch's creep.
if(NOT out MATCHES "Ramp grid: [^\n]*\n\n[^\n]*\n[^\n]*\n\\| stiction \\| rk4 \\| 1e-4 s \\| ${n} \\| ${n} \\| ${n} \\|")
  message(FATAL_ERROR "no stiction rk4 row with creep and breakaway error for the ramp grid")
endif()
if(NOT out MATCHES "Pinch: [^\n]*\n\n[^\n]*\n[^\n]*\n\\| stiction \\| rk4 \\| 1e-4 s \\| ${n} \\| ${n} m \\|")
  message(FATAL_ERROR "no stiction rk4 row with creep for the pinch")
endif()
if(NOT out MATCHES "\\| stiction \\| rk4 \\| 1e-4 s \\| ${n} s \\| ${n} rad \\|")
  message(FATAL_ERROR "no stiction rk4 row with phase and amplitude errors for the pendulum")
endif()
