# output.energy_accounts = false end to end (tests/cli/energy_accounts.py, ~5-10 s): energy.csv
# says which columns were not computed and holds nan in them, the other columns are those of
# the run with the accounts to the last digit, and a restart must keep the setting.
find_program(CGDEM_TEST_PYTHON NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT CGDEM_TEST_PYTHON)
  find_program(CGDEM_TEST_PYTHON NAMES python3)
endif()
# With an MPI launcher, also 2 ranks (tests/cli/mpi_bed.toml) both ways.
set(_mpi "")
if(MPIEXEC_EXECUTABLE)
  set(_mpi --mpiexec ${MPIEXEC_EXECUTABLE} --mpi_case ${PROJECT_SOURCE_DIR}/tests/cli/mpi_bed.toml)
endif()
add_test(NAME cli.energy_accounts_off
         COMMAND ${CGDEM_TEST_PYTHON} ${PROJECT_SOURCE_DIR}/tests/cli/energy_accounts.py --cgdem $<TARGET_FILE:cgdem>
                 --case ${PROJECT_SOURCE_DIR}/tests/cli/base.toml --work ${PROJECT_BINARY_DIR}/cli_out/energy_accounts
                 ${_mpi})
set_tests_properties(cli.energy_accounts_off PROPERTIES LABELS cli TIMEOUT 300 ENVIRONMENT "OMP_NUM_THREADS=1"
                     PASS_REGULAR_EXPRESSION "PASS")
