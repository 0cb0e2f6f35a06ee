# bench/dem/tile_bed.py and `cgdem bench dem --box-x --box-y` (the benchmark on beds larger
# than the shared ones): tests/cli/bench_tiled_bed.py. Needs Debian's python3 with numpy.
find_program(CGDEM_SYSTEM_PYTHON3 python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(CGDEM_SYSTEM_PYTHON3)
  add_test(NAME cli.bench_dem_tiled_bed
           COMMAND ${CGDEM_SYSTEM_PYTHON3} ${PROJECT_SOURCE_DIR}/tests/cli/bench_tiled_bed.py $<TARGET_FILE:cgdem>
                   ${PROJECT_SOURCE_DIR} ${PROJECT_BINARY_DIR}/cli_out/bench_tiled_bed)
  set_tests_properties(cli.bench_dem_tiled_bed PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1"
                       PASS_REGULAR_EXPRESSION "all checks passed")
endif()
