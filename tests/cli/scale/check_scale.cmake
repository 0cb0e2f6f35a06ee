# Runs `cgdem scale` on the CI column collapse, then again (every run must be picked up,
# not rerun) and checks the printed verdicts against what the physics predicts
# (validation/scaling_column_collapse/README.md). Arguments: CGDEM, CASE, WORK, EXPECT
# (a ;-list of regular expressions every one of which must appear in the first output).
file(REMOVE_RECURSE ${WORK})
string(TIMESTAMP t0 "%s")
execute_process(COMMAND ${CGDEM} scale ${CASE} --ratios 1,2 --simply-large 2 --threads 1 --no-plots --output ${WORK}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
string(TIMESTAMP t1 "%s")
math(EXPR wall "${t1} - ${t0}")
message(STATUS "cgdem scale (3 runs + analysis): ${wall} s wall")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cgdem scale failed (${rc}):\n${out}\n${err}")
endif()
string(REGEX MATCHALL "(deviation|observable|pod|verdict) [^\n]*" lines "${out}")
string(REPLACE ";" "\n" lines "${lines}")
message(STATUS "printed:\n${lines}")
foreach(re ${EXPECT})
  if(NOT out MATCHES "${re}")
    message(FATAL_ERROR "expected '${re}' in the output of cgdem scale")
  endif()
endforeach()
foreach(f scale.md budget_summary.csv observables.csv profile.csv budget_l=2.csv deviation_simply_large_2.csv
          pod_solid_fraction_spectrum.csv pod_solid_fraction_angles.csv l=2/case.toml)
  if(NOT EXISTS ${WORK}/${f})
    message(FATAL_ERROR "cgdem scale did not write ${f}")
  endif()
endforeach()
# Again: the finished runs are picked up, and the verdicts are the same.
execute_process(COMMAND ${CGDEM} scale ${CASE} --ratios 1,2 --simply-large 2 --threads 1 --no-plots --output ${WORK}
                OUTPUT_VARIABLE out2 ERROR_VARIABLE err2 RESULT_VARIABLE rc2)
if(NOT rc2 EQUAL 0 OR out2 MATCHES "running \\(" OR NOT out2 MATCHES "simply_large_2: picking up")
  message(FATAL_ERROR "the second cgdem scale did not pick up the finished runs (${rc2}):\n${out2}\n${err2}")
endif()
string(REGEX MATCHALL "verdict [^\n]*" v1 "${out}")
string(REGEX MATCHALL "verdict [^\n]*" v2 "${out2}")
if(NOT v1 STREQUAL v2)
  message(FATAL_ERROR "verdicts differ after pick-up:\n${v1}\n${v2}")
endif()
