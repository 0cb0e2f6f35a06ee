# `cmake --install` gives a working cgdem: the installed binary prints its version and
# revision, and an analysis command run from the install prefix finds its plot scripts
# there (PREFIX/share/cgdem/scripts), not in the source tree: `cgdem compare` on the
# synthetic run folders of compare.cli.cmake must draw curves.png. CITATION.cff carries the
# project version.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  add_test(NAME cli.install.works
           COMMAND ${CMAKE_COMMAND} -DBUILD=${PROJECT_BINARY_DIR} -DPREFIX=${PROJECT_BINARY_DIR}/cli_out/install
                   -DVERSION=${PROJECT_VERSION} -DSRC=${PROJECT_SOURCE_DIR}
                   -DRUNS=${PROJECT_BINARY_DIR}/cli_out/compare_runs -P ${PROJECT_SOURCE_DIR}/tests/cli/install.cli.cmake)
  set_tests_properties(cli.install.works PROPERTIES FIXTURES_REQUIRED compare_runs LABELS cli)
  return()
endif()

cmake_minimum_required(VERSION 3.22)
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${PREFIX} RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD} --prefix ${PREFIX} failed (${rc})")
endif()
foreach(f bin/cgdem share/cgdem/scripts/plot_compare.py share/cgdem/scripts/plot_scale.py
          share/cgdem/scripts/plot_spectrum.py share/cgdem/cases/die_filling/case_1_3.toml
          share/doc/cgdem/LICENSE share/doc/cgdem/CITATION.cff share/doc/cgdem/model.md)
  if(NOT EXISTS ${PREFIX}/${f})
    message(FATAL_ERROR "not installed: ${PREFIX}/${f}")
  endif()
endforeach()
execute_process(COMMAND ${PREFIX}/bin/cgdem --version OUTPUT_VARIABLE out RESULT_VARIABLE rc
                OUTPUT_STRIP_TRAILING_WHITESPACE)
message(STATUS "installed cgdem --version: ${out}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "^cgdem ${VERSION} \\(revision [0-9a-f]+(-dirty)?\\)$")
  message(FATAL_ERROR "cgdem --version printed '${out}' (exit ${rc}); expected 'cgdem ${VERSION} (revision <hash>)'")
endif()
file(STRINGS ${SRC}/CITATION.cff cff_version REGEX "^version: ")
if(NOT cff_version STREQUAL "version: ${VERSION}")
  message(FATAL_ERROR "CITATION.cff says '${cff_version}', the project version is ${VERSION}")
endif()
# Run from a folder outside both trees with the source tree's scripts out of reach.
set(work ${PREFIX}/../install_compare)
file(REMOVE_RECURSE ${work})
file(MAKE_DIRECTORY ${work})
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=CGDEM_SCRIPT_DIR
                        ${PREFIX}/bin/cgdem compare ${RUNS}/with_air ${RUNS}/vacuum --output ${work}/report
                WORKING_DIRECTORY ${work} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "installed cgdem compare failed (${rc}):\n${out}\n${err}")
endif()
file(READ ${work}/report/compare.md md)
if(NOT EXISTS ${work}/report/curves.png)
  if(md MATCHES "not found")
    message(FATAL_ERROR "the installed cgdem did not find its plot scripts:\n${md}")
  endif()
  # No matplotlib on this machine: the scripts were found (else "not found"), the plot not drawn.
  message(STATUS "no curves.png (no python3 with matplotlib?); the report says why")
else()
  message(STATUS "installed cgdem compare drew ${work}/report/curves.png")
endif()
