# validation/lone_parcel_fall (README.md there): one parcel falling from rest through still
# air on the die-filling grid, l = 1, 2, 3, one-way and two-way, against the single-particle
# equation of motion (six runs of one parcel, ~20 s). Needs Debian's python3 with numpy
# and pandas.
find_program(CGDEM_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(CGDEM_SYSTEM_PYTHON3)
  add_test(NAME validation.lone_parcel_fall
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/validation/lone_parcel_fall/run_fall.py check
                   $<TARGET_FILE:cgdem> ${PROJECT_BINARY_DIR}/cli_out/lone_parcel_fall)
  set_tests_properties(validation.lone_parcel_fall PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1"
                       PASS_REGULAR_EXPRESSION "lone parcel fall check passed" TIMEOUT 300)
endif()
