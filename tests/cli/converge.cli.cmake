# `cgdem converge` end to end on the Taylor-Green flow case (tests/cli/converge/*.toml,
# src/app/flow_case.hpp); each check runs in about a second. The printed observed order of
# the finest triple (and the least-squares order when --exact is given) must lie in a band.
set(_cv ${PROJECT_SOURCE_DIR}/tests/cli/converge)
# Space: n = 16, 32, 64 cells, dt = 0.5 x the explicit limit (proportional to dx here), Heun:
# the rms velocity error must fall at least as h^1.8 (second-order scheme; measured 2.48,
# least squares 2.71: limiter clipping at the extrema fades with refinement); a second
# study with --reuse must rerun nothing.
add_test(NAME cli.converge.taylor_green_space
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${_cv}/taylor_green.toml
                 "-DARGS=--vary;flow.n=16,32,64;--h-from;1/value;--metric;u_error_l2_m_s;--exact;u_error_l2_m_s=0"
                 -DMETRIC=u_error_l2_m_s -DP_MIN=1.8 -DP_MAX=1e9 -DREUSE=1
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/converge_space -P ${_cv}/check_order.cmake)
# Time: dt = 0.08, 0.04, 0.02 s on 32^2 (the spatial error is the same at every level and
# cancels in the differences). The amplitude of the vortex mode must converge at the order
# of the integrator: Heun 2 (measured 2.004), forward Euler 1 (measured 1.006); band +- 0.1.
add_test(NAME cli.converge.taylor_green_time_heun
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${_cv}/taylor_green_dt.toml
                 "-DARGS=--vary;flow.dt=0.08,0.04,0.02;--metric;decay_factor"
                 -DMETRIC=decay_factor -DP_MIN=1.9 -DP_MAX=2.1
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/converge_time_heun -P ${_cv}/check_order.cmake)
add_test(NAME cli.converge.taylor_green_time_euler
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${_cv}/taylor_green_dt.toml
                 "-DARGS=--vary;flow.dt=0.08,0.04,0.02;--set;flow.time_order=1;--metric;decay_factor"
                 -DMETRIC=decay_factor -DP_MIN=0.9 -DP_MAX=1.1
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/converge_time_euler -P ${_cv}/check_order.cmake)
set_tests_properties(cli.converge.taylor_green_space cli.converge.taylor_green_time_heun
                     cli.converge.taylor_green_time_euler PROPERTIES LABELS "cli;scaling")

# Bad input: a clear message naming the option, no crash.
foreach(bad
    "levels_not_numbers|--vary;flow.n=16,abc,64|--vary flow.n: level: 'abc' is not a number"
    "two_levels|--vary;flow.n=16,32|an observed order needs at least 3 levels, got 2"
    "unknown_metric|--vary;flow.n=8,16,32;--metric;no_such_metric|no metric 'no_such_metric' \\(it has: u_error_l2_m_s"
    "bad_key|--vary;flow.cells=8,16,32|flow.cells"
    "step_too_large|--vary;flow.dt=0.2,0.1,0.05|exceeds the explicit limit")
  string(REPLACE "|" ";" parts "${bad}")
  list(GET parts 0 name)
  string(REGEX REPLACE "^[^|]*\\|([^|]*)\\|.*$" "\\1" args "${bad}")
  string(REGEX REPLACE "^.*\\|" "" expect "${bad}")
  set(metric_args "")
  if(NOT args MATCHES "--metric")
    set(metric_args "--metric;u_error_l2_m_s")
  endif()
  set(case ${_cv}/taylor_green.toml)
  if(name STREQUAL "step_too_large")
    set(case ${_cv}/taylor_green_dt.toml)
  endif()
  add_test(NAME cli.converge.bad_input.${name}
           COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${case} -DCOMMAND=converge "-DEXTRA=${args};${metric_args};--threads;1"
                   "-DEXPECT=${expect}" -DWORK=${PROJECT_BINARY_DIR}/cli_out/converge_bad_${name}
                   -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
  set_tests_properties(cli.converge.bad_input.${name} PROPERTIES LABELS "cli;scaling")
endforeach()
