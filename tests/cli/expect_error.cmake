# Runs `cgdem run CASE` and passes when it exits non-zero with a message matching EXPECT.
# Used by cli_tests.cmake: -DCGDEM=... -DCASE=... -DEXPECT=... [-DEXTRA=...]
execute_process(COMMAND ${CGDEM} run ${CASE} ${EXTRA} --output ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit code ${rc}\nstderr: ${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit for ${CASE}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match the expected message: ${EXPECT}")
endif()
if(err MATCHES "terminate called|Segmentation|Aborted")
  message(FATAL_ERROR "crashed instead of a clean error")
endif()
