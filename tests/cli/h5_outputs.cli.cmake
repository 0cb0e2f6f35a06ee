# The run folder's HDF5 and XDMF files describe themselves and open in every reader
# (tests/cli/h5_outputs.py: h5py, xml.etree, meshio when installed), and damaged .h5 inputs
# stop with one clear line. Needs Debian's python3 with h5py (scripts/install-deps.sh).
find_program(CGDEM_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(CGDEM_SYSTEM_PYTHON3)
  add_test(NAME cli.h5_outputs_describe_themselves
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/tests/cli/h5_outputs.py $<TARGET_FILE:cgdem>
                   ${PROJECT_SOURCE_DIR}/tests/cli/base.toml ${PROJECT_BINARY_DIR}/cli_out/h5_outputs)
  set_tests_properties(cli.h5_outputs_describe_themselves PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1"
                       PASS_REGULAR_EXPRESSION "all checks passed")
  # The tracer z_start (output.tracer_time) in the particle snapshots, straight and restarted.
  add_test(NAME cli.tracer_carries_start_height
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/tests/cli/tracer.py $<TARGET_FILE:cgdem>
                   ${PROJECT_SOURCE_DIR}/tests/cli/base.toml ${PROJECT_BINARY_DIR}/cli_out/tracer)
  set_tests_properties(cli.tracer_carries_start_height PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1"
                       PASS_REGULAR_EXPRESSION "all checks passed")
  # validation/die_filling/origin.py (the shoe layer the die's powder started in) on a
  # snapshot made by hand whose shares are known.
  add_test(NAME cli.origin_layers_counted
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/tests/cli/origin_layers.py
                   ${PROJECT_BINARY_DIR}/cli_out/origin_layers)
  set_tests_properties(cli.origin_layers_counted PROPERTIES LABELS cli PASS_REGULAR_EXPRESSION "all checks passed")
  # validation/die_filling/impact_definitions.py (the front's speed under several averages)
  # on snapshots made by hand, both die types, whose averages are known.
  add_test(NAME cli.impact_definitions_averaged
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/tests/cli/impact_definitions.py
                   ${PROJECT_BINARY_DIR}/cli_out/impact_definitions)
  set_tests_properties(cli.impact_definitions_averaged PROPERTIES LABELS cli
                       PASS_REGULAR_EXPRESSION "all checks passed")
endif()
