# `mpirun -np N cgdem run` of a case (particles in vacuum or with air) against the
# single-process run, and restarts of its portable checkpoint on other rank counts (issue 6):
#   serial      cgdem run CASE                                  (no launcher)
#   np2         mpirun -np 2 cgdem run CASE                     -> compare with serial
#   half        mpirun -np 2 ... --set time.end=T_HALF, then
#     np3       mpirun -np 3 ... --restart half/checkpoint.bin  -> compare with np2
#     np1       cgdem run ... --restart (a copy), one process   -> compare with np2
# Each comparison is compare_runs on energy.csv, twice: EARLY, at a time when the round-off
# of the different summation order has not grown yet (tolerance EARLY_TOL of the energy
# scale), and at the END, where the granular flow has amplified it into different parcel
# paths and only the bulk agrees (END_TOL of the energy scale and of MOMENTUM_SCALE).
#   -DCGDEM=... -DMPIEXEC=... -DCOMPARE=... -DCASE=... -DWORK=... -DT_HALF=...
#   -DT_EARLY=... -DT_EARLY_RESTART=... -DEARLY_TOL=... -DEND_TOL=... -DMOMENTUM_SCALE=...
file(REMOVE_RECURSE ${WORK})
set(mpirun ${MPIEXEC} --allow-run-as-root --oversubscribe -np)
include(${CMAKE_CURRENT_LIST_DIR}/mpi_compare.cmake)
run(serial ${CGDEM} run ${CASE} --output ${WORK}/serial)
run(np2 ${mpirun} 2 ${CGDEM} run ${CASE} --output ${WORK}/np2)
compare(serial np2 ${T_EARLY} ${EARLY_TOL})
compare(serial np2 -1 ${END_TOL})
run(half ${mpirun} 2 ${CGDEM} run ${CASE} --set time.end=${T_HALF} --output ${WORK}/np3)
file(COPY ${WORK}/np3/ DESTINATION ${WORK}/np1)
run(np3 ${mpirun} 3 ${CGDEM} run ${CASE} --output ${WORK}/np3 --restart ${WORK}/np3/checkpoint.bin)
compare(np2 np3 ${T_EARLY_RESTART} ${EARLY_TOL})
compare(np2 np3 -1 ${END_TOL})
run(np1 ${CGDEM} run ${CASE} --output ${WORK}/np1 --restart ${WORK}/np1/checkpoint.bin)
compare(np2 np1 ${T_EARLY_RESTART} ${EARLY_TOL})
compare(np2 np1 -1 ${END_TOL})
