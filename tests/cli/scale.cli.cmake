# `cgdem scale` end to end on the CI column collapse (validation/scaling_column_collapse):
# l = 1, 2 and the simply-large system in vacuum (about 45 s wall on a loaded 2-core
# machine, 10 s of processor time). Checked: the budget of every run closes, the run-out
# and the centre of mass of l = 2 agree with l = 1, the POD subspaces of both l = 2 and the
# simply-large system agree (in vacuum they differ from the coarse-grained system only by
# their contact time), the second call picks every run up. NOT checked, because this small
# case does not meet it (README there: the column is 4 parcels wide at l = 2): that the
# whole energy budget of l = 2 agrees within the default thresholds.
set(scale_case ${PROJECT_SOURCE_DIR}/validation/scaling_column_collapse/case.toml)
add_test(NAME cli.scale_column_collapse
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${scale_case}
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/scale_column_collapse
                 "-DEXPECT=verdict l=1 budgets: agrees;observable l=2 runout_x95_m: [0-9.e-]+ \\(relative, threshold 0.1\\) agrees;observable l=2 com_x_m: [0-9.e-]+ \\(relative, threshold 0.1\\) agrees;verdict l=2 pod_solid_fraction: agrees;verdict simply_large_2 pod_solid_fraction: agrees"
                 -P ${PROJECT_SOURCE_DIR}/tests/cli/scale/check_scale.cmake)
set_tests_properties(cli.scale_column_collapse PROPERTIES LABELS "cli;scaling" TIMEOUT 300)
# Bad input names the option.
add_test(NAME cli.scale_bad_ratios
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${scale_case}
                 "-DEXPECT=--ratios: must contain 1" "-DEXTRA=--ratios;2,3"
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/scale_bad
                 -DCOMMAND=scale "-DFORBID_OUT=running \\(" -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
add_test(NAME cli.scale_bad_threshold
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${scale_case}
                 "-DEXPECT=--threshold 'energie=0.1': unknown name 'energie'" "-DEXTRA=--threshold;energie=0.1"
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/scale_bad
                 -DCOMMAND=scale "-DFORBID_OUT=running \\(" -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
set_tests_properties(cli.scale_bad_ratios cli.scale_bad_threshold PROPERTIES LABELS "cli;scaling")
