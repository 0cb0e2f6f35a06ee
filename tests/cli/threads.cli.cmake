# Results independent of the thread count, for a coupled run with a moving wall on a grid
# large enough (80 x 60 x 80 cells) that every threaded loop of the air and the coupling
# runs on both threads: the paddle of moving_wall.toml sweeping parcels through air, to
# 0.5 ms (5 fluid steps; about 10 s in all).
add_test(NAME cli.air_threads_bit_identical
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/moving_wall.toml
                 "-DEXTRA=--set;air.dx=1e-4;--set;time.end=5e-4" -DWORK=${PROJECT_BINARY_DIR}/cli_out/threads
                 -P ${PROJECT_SOURCE_DIR}/tests/cli/threads.cmake)
set_tests_properties(cli.air_threads_bit_identical PROPERTIES LABELS cli TIMEOUT 300
                     PASS_REGULAR_EXPRESSION "same state on 1 and 2 threads")
