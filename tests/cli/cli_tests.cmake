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
# The same with the implicit drag coupling (KINSOL): it runs and reports its solves.
add_test(NAME cli.tiny_air_case_runs_implicit_drag
         COMMAND $<TARGET_FILE:cgdem> run ${PROJECT_SOURCE_DIR}/tests/cli/base.toml --set air.dx=1e-3
                 --set air.coupling=implicit --output ${PROJECT_BINARY_DIR}/cli_out/tiny_air_implicit)
set_tests_properties(cli.tiny_air_case_runs_implicit_drag PROPERTIES LABELS cli
  PASS_REGULAR_EXPRESSION "drag: implicit.*KINSOL anderson.*implicit drag: [0-9]+ nonlinear solves.*particles 300 \\(left the domain: 0, centre inside a wall: 0\\)")
# Checkpoint and restart: bit-identical continuation, in vacuum, with air (semi-implicit and
# implicit drag coupling), and with air and a moving wall (the restart lands while the
# paddle accelerates through the parcels).
foreach(variant vacuum air air_implicit_drag moving_wall)
  set(extra "")
  set(case ${PROJECT_SOURCE_DIR}/tests/cli/base.toml)
  if(variant STREQUAL "air")
    set(extra "--set;air.dx=1e-3")
  elseif(variant STREQUAL "air_implicit_drag")
    set(extra "--set;air.dx=1e-3;--set;air.coupling=implicit")
  elseif(variant STREQUAL "moving_wall")
    set(case ${PROJECT_SOURCE_DIR}/tests/cli/moving_wall.toml)
  endif()
  add_test(NAME cli.restart_is_bit_identical_${variant}
           COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${case}
                   "-DEXTRA=${extra}" -DWORK=${PROJECT_BINARY_DIR}/cli_out/restart_${variant}
                   -P ${PROJECT_SOURCE_DIR}/tests/cli/restart.cmake)
  set_tests_properties(cli.restart_is_bit_identical_${variant} PROPERTIES LABELS cli)
endforeach()
# A state settled in vacuum continues with air; an air checkpoint does not continue in vacuum.
add_test(NAME cli.vacuum_checkpoint_continues_with_air
         COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/base.toml
                 -DWORK=${PROJECT_BINARY_DIR}/cli_out/air_after_vacuum -P ${PROJECT_SOURCE_DIR}/tests/cli/air_after_vacuum.cmake)
set_tests_properties(cli.vacuum_checkpoint_continues_with_air PROPERTIES LABELS cli)
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
# Started as several processes of an MPI launcher, every command but `run` stops before it
# does anything (src/app/launcher.hpp), and so does `run` in a build without MPI: the
# launcher's variables as OpenMPI sets them, and, where OpenMPI is installed, a real
# `mpirun -np 2`.
add_test(NAME cli.refuses_several_launcher_processes
         COMMAND ${CMAKE_COMMAND} -E env OMPI_COMM_WORLD_SIZE=3 OMPI_COMM_WORLD_RANK=0
                 ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCOMMAND=spectrum -DCASE=${PROJECT_BINARY_DIR}
                 "-DEXPECT=`cgdem spectrum` was started as 3 processes \\(OMPI_COMM_WORLD_SIZE=3\\), but it runs in one process"
                 "-DFORBID_OUT=spectrum|Welch" -DWORK=${PROJECT_BINARY_DIR}/cli_out/launcher
                 -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
set_tests_properties(cli.refuses_several_launcher_processes PROPERTIES LABELS cli)
if(MPIEXEC_EXECUTABLE)
  add_test(NAME cli.refuses_mpirun_np2
           COMMAND ${CMAKE_COMMAND}
                   "-DCGDEM=${MPIEXEC_EXECUTABLE};--allow-run-as-root;--oversubscribe;${MPIEXEC_NUMPROC_FLAG};2;$<TARGET_FILE:cgdem>"
                   -DCOMMAND=spectrum -DCASE=${PROJECT_BINARY_DIR}
                   "-DEXPECT=`cgdem spectrum` was started as 2 processes \\(OMPI_COMM_WORLD_SIZE=2\\)"
                   "-DFORBID_OUT=Welch" -DWORK=${PROJECT_BINARY_DIR}/cli_out/mpirun_np2
                   -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
  set_tests_properties(cli.refuses_mpirun_np2 PROPERTIES LABELS cli ENVIRONMENT "OMP_NUM_THREADS=1")
endif()
if(CGDEM_MPI)
  # `mpirun -np N cgdem run` against one process, and portable restarts on 3 and 1 ranks
  # (tests/cli/mpi_run.cmake). The runs differ only in the order of the force sums (and, after
  # a restart, in the first list build). Measured (30 ms of pouring 1,000 parcels across the
  # cuts): identical energy rows up to 16 ms (2 ranks) and 2 ms after the restart; then the
  # flow amplifies round-off by ~1e4 per ms, to 1.5e-3 of the energy scale and 5e-3 of
  # MOMENTUM_SCALE (the mass at 0.1 m/s) at 30 ms, with parcel paths 0.5 mm apart. Hence
  # 1e-8 early (a contact force missing at a cut for one step is ~1e-5) and 2e-2 at the end.
  add_executable(compare_runs ${PROJECT_SOURCE_DIR}/tests/cli/compare_runs.cpp)
  target_link_libraries(compare_runs PRIVATE cgdem_io)
  # One mpi_run.cmake test: case, the early comparison times (before / after the restarts).
  function(cgdem_mpi_run_test name case t_early t_early_restart)
    add_test(NAME ${name}
             COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DMPIEXEC=${MPIEXEC_EXECUTABLE}
                     -DCOMPARE=$<TARGET_FILE:compare_runs> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/${case}
                     -DT_HALF=15e-3 -DT_EARLY=${t_early} -DT_EARLY_RESTART=${t_early_restart} -DEARLY_TOL=1e-8
                     -DEND_TOL=2e-2 -DMOMENTUM_SCALE=4e-6 -DWORK=${PROJECT_BINARY_DIR}/cli_out/${name}
                     -P ${PROJECT_SOURCE_DIR}/tests/cli/mpi_run.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli;parallel" TIMEOUT 300 ENVIRONMENT "OMP_NUM_THREADS=1")
  endfunction()
  cgdem_mpi_run_test(cli.mpirun_matches_one_process_and_restarts_on_other_rank_counts mpi_bed.toml 15e-3 17e-3)
  # The same with air (mpi_bed_air.toml: two-way coupling, IBM walls, open top; both pressure
  # solves to 1e-12). Measured: energy rows identical (to the 10 digits written) up to 7 ms on
  # 2 ranks and 1 ms after the restarts at 15 ms on 3 ranks and in one process; the air's
  # round-off (global dot products in another order) then grows ~1e2 per ms, to 5e-13 at 8 ms,
  # 1e-8 at 10 ms and 2e-4 .. 8e-4 of the energy scale, 3.4e-3 of MOMENTUM_SCALE at 30 ms.
  # Tolerances as for the bed in vacuum: 1e-8 early, 2e-2 at the end.
  cgdem_mpi_run_test(cli.mpirun_with_air_matches_one_process_and_restarts_on_other_rank_counts mpi_bed_air.toml
                     7e-3 16e-3)
  # The other way round (tests/cli/mpi_restart.cmake): a checkpoint written by one process (its
  # exact state) restarts on 2 ranks; against the uninterrupted single-process run, at the
  # tolerances above (the same early times after the restart at 15 ms).
  function(cgdem_mpi_restart_test name case t_early_restart)
    add_test(NAME ${name}
             COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DMPIEXEC=${MPIEXEC_EXECUTABLE}
                     -DCOMPARE=$<TARGET_FILE:compare_runs> -DCASE=${PROJECT_SOURCE_DIR}/tests/cli/${case}
                     -DT_HALF=15e-3 -DT_EARLY_RESTART=${t_early_restart} -DEARLY_TOL=1e-8 -DEND_TOL=2e-2
                     -DMOMENTUM_SCALE=4e-6 -DWORK=${PROJECT_BINARY_DIR}/cli_out/${name}
                     -P ${PROJECT_SOURCE_DIR}/tests/cli/mpi_restart.cmake)
    set_tests_properties(${name} PROPERTIES LABELS "cli;parallel" TIMEOUT 300 ENVIRONMENT "OMP_NUM_THREADS=1")
  endfunction()
  cgdem_mpi_restart_test(cli.one_process_checkpoint_restarts_on_two_ranks mpi_bed.toml 17e-3)
  cgdem_mpi_restart_test(cli.one_process_checkpoint_with_air_restarts_on_two_ranks mpi_bed_air.toml 16e-3)
endif()
