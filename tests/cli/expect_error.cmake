# Runs `cgdem COMMAND CASE EXTRA... --output WORK` and passes when it exits non-zero with a
# message matching EXPECT on stderr, without a crash.
#   -DCGDEM=... -DCASE=... -DEXPECT=... -DWORK=... [-DCOMMAND=run] [-DEXTRA=a;b]
#   [-DFORBID_OUT=REGEX: fail if stdout matches, e.g. a run that started before the error]
if(NOT COMMAND)
  set(COMMAND run)
endif()
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CGDEM} ${COMMAND} ${CASE} ${EXTRA} --output ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit code ${rc}\nstderr: ${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit for ${COMMAND} ${CASE}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match the expected message: ${EXPECT}")
endif()
if(err MATCHES "terminate called|Segmentation|Aborted")
  message(FATAL_ERROR "crashed instead of a clean error")
endif()
if(FORBID_OUT AND out MATCHES "${FORBID_OUT}")
  message(FATAL_ERROR "stdout matches '${FORBID_OUT}': the command started work instead of stopping")
endif()
