# cgdem_check_clean_error(RC ERR EXPECT WHAT), for the -P scripts of tests/cli: fails the
# test unless the command exited non-zero (RC) with its stderr (ERR) matching the regular
# expression EXPECT, and without a crash. WHAT ends the message of a zero exit ("" or
# " for ...").
function(cgdem_check_clean_error rc err expect what)
  if(rc EQUAL 0)
    message(FATAL_ERROR "expected a non-zero exit${what}")
  endif()
  if(NOT err MATCHES "${expect}")
    message(FATAL_ERROR "stderr does not match the expected message: ${expect}")
  endif()
  if(err MATCHES "terminate called|Segmentation|Aborted")
    message(FATAL_ERROR "crashed instead of a clean error")
  endif()
endfunction()
