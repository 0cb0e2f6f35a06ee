# Runs `cgdem COMMAND CASE EXTRA... --output WORK` and passes when it exits non-zero with a
# message matching EXPECT on stderr, without a crash.
#   -DCGDEM=... -DCASE=... -DEXPECT=... -DWORK=... [-DCOMMAND=run] [-DEXTRA=a;b]
#   [-DFORBID_OUT=REGEX: fail if stdout matches, e.g. a run that started before the error]
include(${CMAKE_CURRENT_LIST_DIR}/clean_error.cmake)
if(NOT COMMAND)
  set(COMMAND run)
endif()
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CGDEM} ${COMMAND} ${CASE} ${EXTRA} --output ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit code ${rc}\nstderr: ${err}")
cgdem_check_clean_error("${rc}" "${err}" "${EXPECT}" " for ${COMMAND} ${CASE}")
if(FORBID_OUT AND out MATCHES "${FORBID_OUT}")
  message(FATAL_ERROR "stdout matches '${FORBID_OUT}': the command started work instead of stopping")
endif()
