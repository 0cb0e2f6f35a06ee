# The contact-law registry from the command line (src/contact/laws.hpp): a case with the
# Hertz-Mindlin law runs, and restarts bit-identically from its checkpoint (its contact
# histories go through the checkpoint as the linear law's do). Bad [contact] inputs are in
# tests/cli/bad/contact_law_*.toml.
add_test(NAME cli.contact_law_hertz_mindlin_runs
         COMMAND $<TARGET_FILE:cgdem> run ${PROJECT_SOURCE_DIR}/tests/cli/hertz.toml
                 --output ${PROJECT_BINARY_DIR}/cli_out/hertz)
set_tests_properties(cli.contact_law_hertz_mindlin_runs PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "particles 300 \\(left the domain: 0, centre inside a wall: 0\\)")
add_test(NAME cli.restart_is_bit_identical_hertz_mindlin
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/hertz.toml
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/restart_hertz -P ${PROJECT_SOURCE_DIR}/tests/cli/restart.cmake)
set_tests_properties(cli.restart_is_bit_identical_hertz_mindlin PROPERTIES LABELS cli)
