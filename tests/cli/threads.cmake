# The same case on 1 and on 2 threads ends in the same state, bit for bit (the state digest
# hashes the parcels, their contact histories, the air's fields and the books), and the
# second run really had 2 threads (timings.csv's threads column).
#   -DCGDEM=... -DCASE=... -DWORK=... "-DEXTRA=--set;key=value;..."
file(REMOVE_RECURSE ${WORK})
foreach(t 1 2)
  execute_process(COMMAND ${CGDEM} run ${CASE} ${EXTRA} --threads ${t} --output ${WORK}/t${t}
                  OUTPUT_VARIABLE out${t} ERROR_VARIABLE err${t} RESULT_VARIABLE r${t})
  if(NOT r${t} EQUAL 0)
    message(FATAL_ERROR "the run on ${t} thread(s) failed: ${r${t}}\n${out${t}}\n${err${t}}")
  endif()
  string(REGEX MATCH "state digest [0-9a-f]+ at t = [0-9.e-]+" d${t} "${out${t}}")
  file(STRINGS ${WORK}/t${t}/timings.csv rows REGEX ",wall,")
  list(GET rows 0 row)
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 3 threads${t})
endforeach()
message(STATUS "1 thread: ${d1}; 2 threads: ${d2} (timings.csv threads: ${threads1}, ${threads2})")
if(NOT threads1 EQUAL 1 OR NOT threads2 EQUAL 2)
  message(FATAL_ERROR "the runs did not use 1 and 2 threads: ${threads1}, ${threads2}")
endif()
if(NOT d1 OR NOT d1 STREQUAL d2)
  message(FATAL_ERROR "the state on 2 threads differs from that on 1: '${d1}' vs '${d2}'")
endif()
message(STATUS "same state on 1 and 2 threads")
