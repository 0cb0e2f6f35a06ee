# A run stopped at a checkpoint and continued with --restart must end in exactly the state
# of the uninterrupted run (same state digest: DEM particles, contact history, air fields).
#   -DCGDEM=... -DCASE=... -DWORK=... -DEXTRA="--set;air.dx=1e-3" (optional)
file(REMOVE_RECURSE ${WORK})
set(common run ${CASE} --set output.checkpoint_interval=1e-3 ${EXTRA})
execute_process(COMMAND ${CGDEM} ${common} --output ${WORK}/full OUTPUT_VARIABLE full RESULT_VARIABLE r1)
execute_process(COMMAND ${CGDEM} ${common} --set time.end=1e-3 --output ${WORK}/split OUTPUT_VARIABLE first RESULT_VARIABLE r2)
file(COPY_FILE ${WORK}/split/checkpoint.bin ${WORK}/at_1e-3.bin)
execute_process(COMMAND ${CGDEM} ${common} --output ${WORK}/split --restart ${WORK}/split/checkpoint.bin
                OUTPUT_VARIABLE second ERROR_VARIABLE second_err RESULT_VARIABLE r3)
if(NOT r1 EQUAL 0 OR NOT r2 EQUAL 0 OR NOT r3 EQUAL 0)
  message(FATAL_ERROR "a run failed: ${r1} ${r2} ${r3}\n${full}\n${first}\n${second}\n${second_err}")
endif()
string(REGEX MATCH "state digest [0-9a-f]+ at t = [0-9.e-]+" d_full "${full}")
string(REGEX MATCH "state digest [0-9a-f]+ at t = [0-9.e-]+" d_split "${second}")
message(STATUS "uninterrupted: ${d_full}; restarted at 1e-3 s: ${d_split}")
if(NOT d_full OR NOT d_full STREQUAL d_split)
  message(FATAL_ERROR "restart is not bit-identical: '${d_full}' vs '${d_split}'")
endif()
file(READ ${WORK}/full/energy.csv e_full)
file(READ ${WORK}/split/energy.csv e_split)
if(NOT e_full STREQUAL e_split)
  message(FATAL_ERROR "energy.csv of the restarted run differs from the uninterrupted one")
endif()
# A restart whose [particles] differ (here the skin, twice the default of these l = 3
# parcels) rebuilds the checkpoint's neighbour lists at its first step and says so; the
# restart above, of the same case, kept them.
set(rebuilt "neighbour lists are rebuilt at the first step \\(skin 7.5e-05 m\\)")
execute_process(COMMAND ${CGDEM} ${common} --set time.end=2e-3 --set particles.skin=75e-6 --output ${WORK}/new_skin
                        --restart ${WORK}/at_1e-3.bin
                OUTPUT_VARIABLE third ERROR_VARIABLE third_err RESULT_VARIABLE r4)
if(NOT r4 EQUAL 0 OR NOT third_err MATCHES "${rebuilt}")
  message(FATAL_ERROR "the restart with another skin did not say that it rebuilds the lists (${r4}):\n${third_err}\n${third}")
endif()
if(second_err MATCHES "rebuilt at the first step")
  message(FATAL_ERROR "the restart of the same case rebuilt its lists:\n${second_err}")
endif()
message(STATUS "restart with skin 75e-6 m: lists rebuilt at its first step, as it says")
