# docs/case_keys.md is what `cgdem keys` generates from the case readers (src/app/case_keys.hpp):
# the test fails when the committed file differs (regenerate it with
# `build/cgdem keys --output docs/case_keys.md`), or when a case file of the repository uses a key
# the reference lacks.
#   -DCGDEM=... -DREFERENCE=docs/case_keys.md -DWORK=... -DCASES="a.toml;b.toml;..."
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${CGDEM} keys --output ${WORK}/case_keys.md RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cgdem keys failed (${rc}): ${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/case_keys.md ${REFERENCE} RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  execute_process(COMMAND diff ${REFERENCE} ${WORK}/case_keys.md OUTPUT_VARIABLE d)
  message(FATAL_ERROR "${REFERENCE} is out of date: regenerate it with `cgdem keys --output ${REFERENCE}`\n${d}")
endif()
message(STATUS "${REFERENCE} is what cgdem keys generates")
execute_process(COMMAND ${CGDEM} keys --check ${CASES} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "case files of the repository use keys that the reference lacks (above)")
endif()
