# air_steps.csv, the per-step record of the fluid solves of a run with air: one row per fluid
# step that adds up to the final report's "fluid steps ..." and "implicit drag: ..." figures,
# semi-implicit and implicit, straight and continued after a restart, and no file in vacuum
# (tests/cli/air_steps.py: nine runs of tests/cli/moving_wall.toml of about a second each).
# Needs Debian's python3 with numpy and pandas (scripts/install-deps.sh).
find_program(CGDEM_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(CGDEM_SYSTEM_PYTHON3)
  add_test(NAME cli.air_steps_record_every_fluid_step
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/tests/cli/air_steps.py $<TARGET_FILE:cgdem>
                   ${PROJECT_SOURCE_DIR}/tests/cli/moving_wall.toml ${PROJECT_BINARY_DIR}/cli_out/air_steps)
  set_tests_properties(cli.air_steps_record_every_fluid_step PROPERTIES LABELS cli TIMEOUT 300
                       ENVIRONMENT "OMP_NUM_THREADS=1" PASS_REGULAR_EXPRESSION "all checks passed")
endif()
