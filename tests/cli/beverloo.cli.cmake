# Quick mode of validation/beverloo_discharge (README.md there): a half-height bin of l = 3
# parcels fills, then discharges through a 6 d slot in vacuum; the rate must match the
# Beverloo slot law with the sweep's fitted C' and k, and stay steady over the window
# (check_quick.py prints both errors). Needs Debian's python3 with h5py, numpy and pandas.
find_program(CGDEM_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(CGDEM_SYSTEM_PYTHON3)
  add_test(NAME validation.beverloo_discharge_quick
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/validation/beverloo_discharge/check_quick.py
                   $<TARGET_FILE:cgdem> ${PROJECT_BINARY_DIR}/cli_out/beverloo_quick)
  set_tests_properties(validation.beverloo_discharge_quick PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1"
                       PASS_REGULAR_EXPRESSION "beverloo quick check passed" TIMEOUT 300)
endif()
