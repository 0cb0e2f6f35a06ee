# Quick mode of validation/fill_ratio (README.md there): a small die under the paper's shoe
# geometry scaled down (688 parcels at l = 3); the slow pass in vacuum fills the die, the
# fast one does not, and with air the slow pass brings at least 0.10 less of the die's fill
# (check_quick.py prints every figure). Needs Debian's python3 with h5py, numpy and pandas.
find_program(CGDEM_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(CGDEM_SYSTEM_PYTHON3)
  add_test(NAME validation.fill_ratio_quick
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/validation/fill_ratio/check_quick.py
                   $<TARGET_FILE:cgdem> ${PROJECT_BINARY_DIR}/cli_out/fill_ratio_quick)
  set_tests_properties(validation.fill_ratio_quick PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1"
                       PASS_REGULAR_EXPRESSION "fill ratio quick check passed" TIMEOUT 600)
endif()
