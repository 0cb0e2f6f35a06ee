# Runs `cgdem scale CASE EXTRA...` and passes when it exits non-zero, before running
# anything, with a message matching EXPECT on stderr. -DCGDEM -DCASE -DEXPECT -DEXTRA -DWORK
execute_process(COMMAND ${CGDEM} scale ${CASE} ${EXTRA} --output ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit code ${rc}\nstderr: ${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match the expected message: ${EXPECT}")
endif()
if(err MATCHES "terminate called|Segmentation|Aborted" OR out MATCHES "running \\(")
  message(FATAL_ERROR "crashed or started a run instead of a clean error")
endif()
