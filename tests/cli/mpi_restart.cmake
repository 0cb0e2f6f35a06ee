# A checkpoint written by one process restarts on 2 MPI ranks (one checkpoint format for any
# number of ranks, solvers/run/run_checkpoint.hpp); mpi_run.cmake restarts the ranks'
# checkpoints on 3 ranks and on one process:
#   serial   cgdem run CASE                                      (no launcher)
#   half     cgdem run CASE --set time.end=T_HALF                (no launcher), then
#     np2    mpirun -np 2 ... --restart half/checkpoint.bin      -> compare with serial
# The rows up to T_HALF are the ones the single process wrote; after it the runs differ in
# the order of the force sums (and of the pressure solve's dot products), as in mpi_run.cmake.
#   -DCGDEM=... -DMPIEXEC=... -DCOMPARE=... -DCASE=... -DWORK=... -DT_HALF=...
#   -DT_EARLY_RESTART=... -DEARLY_TOL=... -DEND_TOL=... -DMOMENTUM_SCALE=...
file(REMOVE_RECURSE ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/mpi_compare.cmake)
run(serial ${CGDEM} run ${CASE} --output ${WORK}/serial)
run(half ${CGDEM} run ${CASE} --set time.end=${T_HALF} --output ${WORK}/np2)
run(np2 ${MPIEXEC} --allow-run-as-root --oversubscribe -np 2 ${CGDEM} run ${CASE} --output ${WORK}/np2
    --restart ${WORK}/np2/checkpoint.bin)
compare(serial np2 ${T_HALF} 0)
compare(serial np2 ${T_EARLY_RESTART} ${EARLY_TOL})
compare(serial np2 -1 ${END_TOL})
