# Quick mode of validation/discharge_air (README.md there): the half-height Beverloo bin of
# l = 3 parcels settles in vacuum, then discharges through a 6 d slot from that one state in
# vacuum, with air and an open top, and with air and a sealed top; the sealed bin must flow
# at less than half the vacuum rate, the open one in between, and each rate with air must
# match Crewdson et al.'s effective gravity with the measured outlet gradient
# (check_quick.py prints every error). Needs Debian's python3 with h5py, numpy and pandas.
find_program(CGDEM_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(CGDEM_SYSTEM_PYTHON3)
  add_test(NAME validation.discharge_air_quick
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/validation/discharge_air/check_quick.py
                   $<TARGET_FILE:cgdem> ${PROJECT_BINARY_DIR}/cli_out/discharge_air_quick)
  set_tests_properties(validation.discharge_air_quick PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1"
                       PASS_REGULAR_EXPRESSION "air discharge quick check passed" TIMEOUT 600)
endif()
