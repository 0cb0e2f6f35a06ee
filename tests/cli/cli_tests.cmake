# Command-line checks: every bad input in tests/cli/bad/*.toml (first line "# expect: REGEX")
# must stop with that message and a non-zero exit; a tiny valid case must run.
file(GLOB bad_cases CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/cli/bad/*.toml)
foreach(f ${bad_cases})
  get_filename_component(name ${f} NAME_WE)
  file(STRINGS ${f} first LIMIT_COUNT 1)
  string(REGEX REPLACE "^# expect: " "" expect "${first}")
  add_test(NAME cli.bad_input.${name}
           COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${f} "-DEXPECT=${expect}"
                   -DWORK=${PROJECT_BINARY_DIR}/cli_out/${name} -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
  set_tests_properties(cli.bad_input.${name} PROPERTIES LABELS cli)
endforeach()
add_test(NAME cli.bad_set_syntax
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/base.toml
                 "-DEXPECT=--set 'time.end': expected key.path=value" -DEXTRA=--set=time.end
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/bad_set -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
add_test(NAME cli.tiny_case_runs
         COMMAND $<TARGET_FILE:cgdem> run ${PROJECT_SOURCE_DIR}/tests/cli/base.toml --output ${PROJECT_BINARY_DIR}/cli_out/tiny)
set_tests_properties(cli.tiny_case_runs PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "particles 300 \\(left the domain: 0, centre inside a wall: 0\\)")
set_tests_properties(cli.bad_set_syntax PROPERTIES LABELS cli)
# The same tiny case with air (a coupled run on a 6 x 6 x 11 grid of 1 mm).
add_test(NAME cli.tiny_air_case_runs
         COMMAND $<TARGET_FILE:cgdem> run ${PROJECT_SOURCE_DIR}/tests/cli/base.toml --set air.dx=1e-3
                 --output ${PROJECT_BINARY_DIR}/cli_out/tiny_air)
set_tests_properties(cli.tiny_air_case_runs PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "air: 6 x 6 x 11 cells.*particles 300 \\(left the domain: 0, centre inside a wall: 0\\)")
# Checkpoint and restart: bit-identical continuation, in vacuum, with air, and with air
# and a moving wall (the restart lands while the paddle accelerates through the parcels).
foreach(variant vacuum air moving_wall)
  set(extra "")
  set(case ${PROJECT_SOURCE_DIR}/tests/cli/base.toml)
  if(variant STREQUAL "air")
    set(extra "--set;air.dx=1e-3")
  elseif(variant STREQUAL "moving_wall")
    set(case ${PROJECT_SOURCE_DIR}/tests/cli/moving_wall.toml)
  endif()
  add_test(NAME cli.restart_is_bit_identical_${variant}
           COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${case}
                   "-DEXTRA=${extra}" -DWORK=${PROJECT_BINARY_DIR}/cli_out/restart_${variant}
                   -P ${PROJECT_SOURCE_DIR}/tests/cli/restart.cmake)
  set_tests_properties(cli.restart_is_bit_identical_${variant} PROPERTIES LABELS cli)
endforeach()
# Parcels leaving the domain are announced and counted.
add_test(NAME cli.escaping_parcels_are_reported
         COMMAND $<TARGET_FILE:cgdem> run ${PROJECT_SOURCE_DIR}/tests/cli/escape.toml --output ${PROJECT_BINARY_DIR}/cli_out/escape)
set_tests_properties(cli.escaping_parcels_are_reported PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "more parcel\\(s\\) left the domain.*particles 1[0-9] \\(left the domain: [1-9],")
# The settled state (t = 0) is saved and a run from it continues bit-identically.
add_test(NAME cli.settled_state_reruns_bit_identically
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/base.toml
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/settled -P ${PROJECT_SOURCE_DIR}/tests/cli/settled.cmake)
set_tests_properties(cli.settled_state_reruns_bit_identically PROPERTIES LABELS cli)
# Started as several processes of an MPI launcher, `cgdem run` stops before it runs
# anything (src/app/launcher.hpp): the launcher's variables as OpenMPI sets them, and, where
# OpenMPI is installed, a real `mpirun -np 2`.
add_test(NAME cli.refuses_several_launcher_processes
         COMMAND ${CMAKE_COMMAND} -E env OMPI_COMM_WORLD_SIZE=3 OMPI_COMM_WORLD_RANK=0
                 ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/base.toml
                 "-DEXPECT=`cgdem run` was started as 3 processes \\(OMPI_COMM_WORLD_SIZE=3\\), but it runs in one process"
                 "-DFORBID_OUT=particles|output" -DWORK=${PROJECT_BINARY_DIR}/cli_out/launcher
                 -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
set_tests_properties(cli.refuses_several_launcher_processes PROPERTIES LABELS cli)
if(MPIEXEC_EXECUTABLE)
  add_test(NAME cli.refuses_mpirun_np2
           COMMAND ${CMAKE_COMMAND}
                   "-DCGDEM=${MPIEXEC_EXECUTABLE};--allow-run-as-root;--oversubscribe;${MPIEXEC_NUMPROC_FLAG};2;$<TARGET_FILE:cgdem>"
                   -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/base.toml
                   "-DEXPECT=`cgdem run` was started as 2 processes \\(OMPI_COMM_WORLD_SIZE=2\\)"
                   "-DFORBID_OUT=particles" -DWORK=${PROJECT_BINARY_DIR}/cli_out/mpirun_np2
                   -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
  set_tests_properties(cli.refuses_mpirun_np2 PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1")
endif()
