# Failure cases of `cgdem run` (each prints what it tried and its counts):
#   cli.failures.set_value_names_command_line   an error in --set names the option
#   cli.failures.fuzzed_case_files    200 mutated case files through `cgdem run --check`
#                                     (tests/cli/fuzz_cases.py): no crash, every rejection names
#                                     file:line and key (or the --set option), no wrong acceptance
#   cli.failures.kill_mid_write       SIGKILL during snapshot and checkpoint writing, then every
#                                     .h5 / .xdmf read and a restart to the uninterrupted digest
#   cli.failures.restart_die_filling_air  the die filling with air restarted at T/2: final
#                                     snapshots, digests and CSV series bitwise equal
#   cli.failures.output_unwritable    an output folder that cannot be made and a file-size limit
#                                     (EFBIG): a message naming the file, earlier files intact
# A value given with --set is the command line's error, not the file's.
add_test(NAME cli.failures.set_value_names_command_line
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/base.toml
                 "-DEXPECT=error: command line \\(--set 'contact.restitution=2'\\): key 'contact.restitution': expected a number in \\(0, 1\\], got 2"
                 "-DEXTRA=--set;contact.restitution=2" -DWORK=${PROJECT_BINARY_DIR}/cli_out/set_value
                 -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
set_tests_properties(cli.failures.set_value_names_command_line PROPERTIES LABELS cli)
# Python: /usr/bin/python3 (Debian's, with h5py and numpy) when present.
find_program(CGDEM_TEST_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT CGDEM_TEST_PYTHON)
  find_program(CGDEM_TEST_PYTHON NAMES python3)
endif()
if(CGDEM_TEST_PYTHON)
  set(_cli ${PROJECT_SOURCE_DIR}/tests/cli)
  set(_out ${PROJECT_BINARY_DIR}/cli_out/failures)
  add_test(NAME cli.failures.fuzzed_case_files
           COMMAND ${CGDEM_TEST_PYTHON} ${_cli}/fuzz_cases.py --cgdem $<TARGET_FILE:cgdem> --root ${PROJECT_SOURCE_DIR}
                   --work ${_out}/fuzz --count 200 --seed 21)
  add_test(NAME cli.failures.kill_mid_write
           COMMAND ${CGDEM_TEST_PYTHON} ${_cli}/kill_mid_write.py --cgdem $<TARGET_FILE:cgdem> --case ${_cli}/base.toml
                   --work ${_out}/kill --kills 12 --seed 7)
  add_test(NAME cli.failures.restart_die_filling_air
           COMMAND ${CGDEM_TEST_PYTHON} ${_cli}/restart_die_filling.py --cgdem $<TARGET_FILE:cgdem>
                   --case ${PROJECT_SOURCE_DIR}/validation/die_filling/case_1_3.toml --work ${_out}/restart_die)
  add_test(NAME cli.failures.output_unwritable
           COMMAND ${CGDEM_TEST_PYTHON} ${_cli}/output_failures.py --cgdem $<TARGET_FILE:cgdem> --case ${_cli}/base.toml
                   --work ${_out}/output)
  set_tests_properties(cli.failures.fuzzed_case_files cli.failures.kill_mid_write cli.failures.restart_die_filling_air
                       cli.failures.output_unwritable PROPERTIES LABELS cli TIMEOUT 300 ENVIRONMENT "OMP_NUM_THREADS=1")
else()
  message(STATUS "cgdem: no python3: the cli.failures.* tests are not registered")
endif()
