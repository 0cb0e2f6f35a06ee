# The two steps of the multi-rank command-line tests (mpi_run.cmake, mpi_restart.cmake):
#   run(NAME COMMAND...)           runs a command, stops the test when it fails
#   compare(A B AT TOL)            compare_runs on WORK/A and WORK/B at time AT (-1: the end),
#                                  within TOL of the energy scale and of MOMENTUM_SCALE
# Needs WORK, COMPARE and MOMENTUM_SCALE.
function(run name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX MATCH "MPI: [^\n]*" ranks "${out}")
  message(STATUS "${name}: exit ${rc}; ${ranks}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name} failed (${rc}):\n${out}\n${err}")
  endif()
endfunction()
function(compare a b at tol)
  execute_process(COMMAND ${COMPARE} ${WORK}/${a} ${WORK}/${b} --at ${at} --rel-tol ${tol}
                          --momentum-scale ${MOMENTUM_SCALE}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${a} vs ${b} at t = ${at} s (-1: the end):\n${out}${err}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${a} and ${b} differ beyond the tolerances at t = ${at} s")
  endif()
endfunction()
