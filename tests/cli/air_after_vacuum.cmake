# A state settled in vacuum continues with air (solvers/run/run_checkpoint.hpp): the restart
# says that the air starts at rest, the parcels are those of the checkpoint, the air then does
# work on them; and an air checkpoint is refused by a case in vacuum, with the reason.
#   -DCGDEM=... -DCASE=... -DWORK=...
file(REMOVE_RECURSE ${WORK})
set(common run ${CASE} --set output.checkpoint_interval=1e-3)
execute_process(COMMAND ${CGDEM} ${common} --set time.end=1e-3 --output ${WORK}/vacuum
                OUTPUT_VARIABLE out1 ERROR_VARIABLE err1 RESULT_VARIABLE r1)
execute_process(COMMAND ${CGDEM} ${common} --set air.dx=1e-3 --output ${WORK}/air
                --restart ${WORK}/vacuum/checkpoint.bin OUTPUT_VARIABLE out2 ERROR_VARIABLE err2 RESULT_VARIABLE r2)
if(NOT r1 EQUAL 0 OR NOT r2 EQUAL 0)
  message(FATAL_ERROR "a run failed: ${r1} ${r2}\n${out1}${err1}\n${out2}${err2}")
endif()
if(NOT out2 MATCHES "holds no air \\(a run in vacuum\\): the air starts at rest around its parcels at t = 0.001 s")
  message(FATAL_ERROR "the restart did not say that the air starts at rest:\n${out2}")
endif()
# The air run goes on from the checkpoint's time (its first row is t = 1.1 ms, one energy
# interval later), with the vacuum run's parcels (count and mass to the digit), and the air
# works on them (W_air_J, the 10th column, not 0).
file(STRINGS ${WORK}/vacuum/energy.csv v_rows REGEX "^0\\.001,")
file(STRINGS ${WORK}/air/energy.csv a_rows REGEX "^[0-9]")
list(GET v_rows 0 v_row)
list(GET a_rows 0 a_row)
string(REPLACE "," ";" v_cols "${v_row}")
string(REPLACE "," ";" a_cols "${a_row}")
list(GET a_cols 0 a_t)
list(GET a_cols 9 a_wair)
list(SUBLIST v_cols 14 2 v_mass_n)
list(SUBLIST a_cols 14 2 a_mass_n)
message(STATUS "first row of the air run: t = ${a_t} s, W_air = ${a_wair} J, mass and parcels ${a_mass_n} (vacuum at 1 ms: ${v_mass_n})")
if(NOT a_t STREQUAL "0.0011" OR NOT v_mass_n STREQUAL a_mass_n OR a_wair STREQUAL "0")
  message(FATAL_ERROR "the air run does not continue the vacuum run's state with air:\n${v_row}\n${a_row}")
endif()
if(NOT out2 MATCHES "fluid steps [1-9]")
  message(FATAL_ERROR "the air run took no fluid step:\n${out2}")
endif()
execute_process(COMMAND ${CGDEM} ${common} --output ${WORK}/back --restart ${WORK}/air/checkpoint.bin
                OUTPUT_VARIABLE out3 ERROR_VARIABLE err3 RESULT_VARIABLE r3)
message(STATUS "air checkpoint in a vacuum case: ${err3}")
if(r3 EQUAL 0 OR NOT err3 MATCHES "was written by a run with air, the case runs without air")
  message(FATAL_ERROR "an air checkpoint restarted a vacuum case (${r3}):\n${out3}${err3}")
endif()
