# Runs `cgdem spectrum` on synthetic run folders generated here and checks its output.
#   -DCGDEM=... -DWORK=... "-DARGS=arg;arg" (%WORK% is replaced) "-DEXPECT=REGEX" [-DFAIL=ON]
# Folders (dt = 0.2 ms, fs = 5 kHz, 512 rows, t written as a whole number of 1e-4 s):
#   run/     p_A = sin(2 pi n/8)  (625 Hz), p_B = sin(2 pi n/32) (156.25 Hz),
#            p_C = sin(2 pi 3n/32) (468.75 Hz): sines taken from a table of sin(2 pi k/32)
#   jitter/  as run/ but one output interval of 0.3 ms instead of 0.2 ms
#   nop/     no p_ column
# FAIL=ON: must exit non-zero with stderr matching EXPECT and no crash; otherwise must exit
# 0 with stdout matching EXPECT and write the four report files.
cmake_minimum_required(VERSION 3.22)
include(${CMAKE_CURRENT_LIST_DIR}/../clean_error.cmake)
file(REMOVE_RECURSE ${WORK})
set(sin32 0 0.195090322 0.3826834324 0.555570233 0.7071067812 0.8314696123 0.9238795325 0.9807852804 1
    0.9807852804 0.9238795325 0.8314696123 0.7071067812 0.555570233 0.3826834324 0.195090322 0 -0.195090322
    -0.3826834324 -0.555570233 -0.7071067812 -0.8314696123 -0.9238795325 -0.9807852804 -1 -0.9807852804
    -0.9238795325 -0.8314696123 -0.7071067812 -0.555570233 -0.3826834324 -0.195090322)
set(run "# synthetic run (tests/cli/spectrum_data/spectrum_check.cmake)\nt,mass_in_die,transfer_rate,impacts,p_A,p_B,p_C\n")
set(jitter "${run}")
set(nop "# no pressure\nt,mass_in_die\n")
foreach(n RANGE 511)
  math(EXPR ka "(4 * ${n}) % 32")
  math(EXPR kb "${n} % 32")
  math(EXPR kc "(3 * ${n}) % 32")
  list(GET sin32 ${ka} a)
  list(GET sin32 ${kb} b)
  list(GET sin32 ${kc} c)
  math(EXPR t "2 * ${n}")
  set(tj ${t})
  if(n GREATER 300)
    math(EXPR tj "${t} + 1")
  endif()
  string(APPEND run "${t}e-4,0,0,0,${a},${b},${c}\n")
  string(APPEND jitter "${tj}e-4,0,0,0,${a},${b},${c}\n")
  string(APPEND nop "${t}e-4,0\n")
endforeach()
file(WRITE ${WORK}/run/diagnostics.csv "${run}")
file(WRITE ${WORK}/jitter/diagnostics.csv "${jitter}")
file(WRITE ${WORK}/nop/diagnostics.csv "${nop}")

string(REPLACE "%WORK%" "${WORK}" args "${ARGS}")
execute_process(COMMAND ${CGDEM} spectrum ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("cgdem spectrum ${args}\nexit code ${rc}\nstdout:\n${out}\nstderr:\n${err}")
if(FAIL)
  cgdem_check_clean_error("${rc}" "${err}" "${EXPECT}" "")
  return()
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cgdem spectrum failed")
endif()
if(NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "stdout does not match: ${EXPECT}")
endif()
string(REGEX MATCH "wrote ([^\n]*)/spectrum.md" _ "${out}")
foreach(f spectrum.md psd.csv coherence.csv peaks.csv)
  if(NOT EXISTS ${CMAKE_MATCH_1}/${f})
    message(FATAL_ERROR "missing ${CMAKE_MATCH_1}/${f}")
  endif()
endforeach()
