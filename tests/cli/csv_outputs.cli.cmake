# Every CSV file of a die-filling run with air describes itself and reads with numpy and
# pandas as is (src/io/csv_series.hpp): `cgdem run tests/cli/die_tiny.toml` (~10 s), then
# tests/cli/csv_outputs/check_csv.py on its folder (numpy.genfromtxt(names=True,
# comments="#"), pandas.read_csv(comment="#"): the same names and rows, numbers only, unit
# suffixes, a description line per column, the revision line), after its self-test: the
# same checks must fail on files of the layout before units. Needs python3 with numpy and
# pandas (scripts/install-deps.sh installs python3-numpy and python3-pandas).
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli.csv_outputs_describe_themselves
           COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/die_tiny.toml
                   -DCHECK=${PROJECT_SOURCE_DIR}/tests/cli/csv_outputs/check_csv.py
                   -DWORK=${PROJECT_BINARY_DIR}/cli_out/csv_outputs -P ${PROJECT_SOURCE_DIR}/tests/cli/csv_outputs.cli.cmake)
  set_tests_properties(cli.csv_outputs_describe_themselves PROPERTIES LABELS cli TIMEOUT 300
                       ENVIRONMENT "OMP_NUM_THREADS=1")
  return()
endif()

cmake_minimum_required(VERSION 3.22)
# A python3 that has numpy and pandas: $CGDEM_PYTHON, python3 on PATH, /usr/bin/python3.
set(python "")
foreach(candidate "$ENV{CGDEM_PYTHON}" python3 /usr/bin/python3)
  if(candidate STREQUAL "")
    continue()
  endif()
  execute_process(COMMAND ${candidate} -c "import numpy, pandas" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if(rc EQUAL 0)
    set(python ${candidate})
    break()
  endif()
endforeach()
if(NOT python)
  message(FATAL_ERROR "no python3 with numpy and pandas ($CGDEM_PYTHON, python3, /usr/bin/python3): "
                      "scripts/install-deps.sh installs python3-numpy and python3-pandas")
endif()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${python} ${CHECK} --self-test ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${python} check_csv.py --self-test (the layout before units must fail)\n${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the self-test failed: the checks do not reject the old layout")
endif()
execute_process(COMMAND ${CGDEM} run ${CASE} --output ${WORK}/run RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cgdem run ${CASE} failed (exit ${rc}):\n${out}\n${err}")
endif()
string(REGEX MATCH "[^\n]*outputs in[^\n]*" outputs "${out}")
message("cgdem run: ${outputs}")
execute_process(COMMAND ${python} ${CHECK} ${WORK}/run RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "some CSV files of ${WORK}/run do not describe themselves (above)")
endif()
