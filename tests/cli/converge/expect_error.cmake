# Runs `cgdem converge CASE ARGS` and passes when it exits non-zero with a message matching
# EXPECT on stderr (and no crash).  -DCGDEM=... -DCASE=... -DARGS="..." -DEXPECT=... -DWORK=...
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CGDEM} converge ${CASE} ${ARGS} --output ${WORK} --threads 1
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit code ${rc}\nstderr: ${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match the expected message: ${EXPECT}")
endif()
if(err MATCHES "terminate called|Segmentation|Aborted")
  message(FATAL_ERROR "crashed instead of a clean error")
endif()
