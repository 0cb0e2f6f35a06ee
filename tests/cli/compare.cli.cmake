# `cgdem compare` end to end on synthetic run folders that this file writes when it runs as
# a script with -DMODE=write (the fixture cli.compare.write_runs): the same die filling
# "with_air" and in "vacuum" (t = 0 .. 0.3 s every 1 ms; mass_in_die = t and 2t kg,
# transfer_rate 1 and 1.5 kg/s, p_A = 1 + t Pa with air and NaN in vacuum, mass_in_shoe and
# Q_cavity beyond the usual columns, config.resolved.toml differing in air.enabled), "later"
# (t = 0.4 .. 0.7 s), and folders without metrics.csv / diagnostics.csv. Each test runs in
# well under a second.
if(NOT CMAKE_SCRIPT_MODE_FILE)
  set(_cmp ${PROJECT_BINARY_DIR}/cli_out/compare_runs)
  add_test(NAME cli.compare.write_runs COMMAND ${CMAKE_COMMAND} -DMODE=write -DWORK=${_cmp}
                                               -P ${PROJECT_SOURCE_DIR}/tests/cli/compare.cli.cmake)
  set_tests_properties(cli.compare.write_runs PROPERTIES FIXTURES_SETUP compare_runs LABELS "cli;scaling")
  # A comparison that must succeed, print EXPECT and write a report checked by MODE=check.
  function(compare_cli_test name expect)
    add_test(NAME cli.compare.${name}
             COMMAND ${CMAKE_COMMAND} -DMODE=check -DCGDEM=$<TARGET_FILE:cgdem> -DWORK=${_cmp}
                     -DOUT=${PROJECT_BINARY_DIR}/cli_out/compare_${name} "-DARGS=${ARGN}" "-DEXPECT=${expect}"
                     -P ${PROJECT_SOURCE_DIR}/tests/cli/compare.cli.cmake)
    set_tests_properties(cli.compare.${name} PROPERTIES FIXTURES_REQUIRED compare_runs LABELS "cli;scaling")
  endfunction()
  # Default output folder compare_with_air_vacuum in the working folder; the printed key
  # difference and L2 distances (2t vs t: exactly 1; the same mass_in_shoe: 0; p_A NaN in
  # vacuum: missing); the report, CSV files, carried-through columns and plots checked below.
  compare_cli_test(air_vs_vacuum
                   "config air.enabled: with_air=true, vacuum=false.*curve mass_in_die vacuum: normalised L2 1\n.*curve p_A vacuum: normalised L2 missing.*curve mass_in_shoe vacuum: normalised L2 0\n.*wrote compare_with_air_vacuum/compare.md"
                   %WORK%/with_air %WORK%/vacuum)
  compare_cli_test(labels_and_output "curve transfer_rate vac: normalised L2 0.5\n.*wrote [^\n]*/out/compare.md"
                   %WORK%/with_air %WORK%/vacuum --labels air,vac --output %OUT%/out --dt 0.05 --no-plot)
  # Bad input: non-zero exit, the folder and the file named (tests/cli/expect_error.cmake
  # runs `cgdem compare CASE EXTRA --output WORK`).
  foreach(bad
      "missing_folder|with_air|absent|run folder '[^']*/absent' does not exist"
      "missing_metrics|with_air|nometrics|run folder '[^']*/nometrics' has no metrics.csv"
      "missing_diagnostics|nodiag|vacuum|run folder '[^']*/nodiag' has no diagnostics.csv"
      "one_run|with_air||give at least two run folders \\(got 1\\)"
      "no_common_range|with_air|later|the runs have no common time range")
    string(REPLACE "|" ";" parts "${bad}")
    list(GET parts 0 name)
    list(GET parts 1 a)
    list(GET parts 2 b)
    list(GET parts 3 expect)
    set(extra "")
    if(b)
      set(extra ${_cmp}/${b})
    endif()
    add_test(NAME cli.compare.${name}
             COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DCOMMAND=compare -DCASE=${_cmp}/${a} -DEXTRA=${extra}
                     "-DEXPECT=${expect}" -DWORK=${PROJECT_BINARY_DIR}/cli_out/compare_bad_${name}
                     -P ${PROJECT_SOURCE_DIR}/tests/cli/expect_error.cmake)
    set_tests_properties(cli.compare.${name} PROPERTIES FIXTURES_REQUIRED compare_runs LABELS "cli;scaling")
  endforeach()
  return()
endif()

# Script mode. -DMODE=write -DWORK=...: writes the run folders into WORK.
# -DMODE=check -DCGDEM=... -DWORK=... -DOUT=... "-DARGS=arg;arg" (%WORK%, %OUT% replaced)
# "-DEXPECT=REGEX": runs `cgdem compare ARGS` in OUT, which must exit 0 with stdout matching
# EXPECT and write the report files checked below.
cmake_minimum_required(VERSION 3.22)
if(MODE STREQUAL "write")
  file(REMOVE_RECURSE ${WORK})
  set(air "# cgdem abc123, case die.toml\nt,mass_in_die,transfer_rate,impacts,p_A,p_B,p_C,mass_in_shoe,Q_cavity,bubbles\n")
  set(vac "${air}")
  set(later "${air}")
  foreach(n RANGE 300)
    math(EXPR n2 "2 * ${n}")
    math(EXPR shoe "1000 - ${n}")
    math(EXPR n_later "${n} + 400")
    math(EXPR p_a "1000 + ${n}")
    string(APPEND air "${n}e-3,${n}e-3,1,${n},${p_a}e-3,0.5,0.25,${shoe}e-3,${n}e-4,nan\n")
    string(APPEND vac "${n}e-3,${n2}e-3,1.5,${n},nan,nan,nan,${shoe}e-3,${n}e-4,nan\n")
    string(APPEND later "${n_later}e-3,0,0,0,0,0,0,0,0,nan\n")
  endforeach()
  set(config "[air]\nenabled = %AIR%\ndx = 0.0006\n[time]\nend = 0.3\n")
  file(WRITE ${WORK}/with_air/diagnostics.csv "${air}")
  file(WRITE ${WORK}/vacuum/diagnostics.csv "${vac}")
  file(WRITE ${WORK}/later/diagnostics.csv "${later}")
  file(WRITE ${WORK}/nodiag/metrics.csv "name,value\nfill_mass_kg,1\n")
  file(WRITE ${WORK}/nometrics/diagnostics.csv "${air}")
  file(WRITE ${WORK}/with_air/metrics.csv "name,value\nfill_mass_kg,0.002\np_B_peak_Pa,15.5\nfront_time_s,0.1\n")
  file(WRITE ${WORK}/vacuum/metrics.csv "name,value\nfill_mass_kg,0.003\np_B_peak_Pa,nan\nfront_time_s,0.08\n")
  file(WRITE ${WORK}/later/metrics.csv "name,value\nfill_mass_kg,0\n")
  string(REPLACE "%AIR%" "true" c "${config}")
  file(WRITE ${WORK}/with_air/config.resolved.toml "# cgdem abc123 resolved configuration of die.toml\n${c}")
  string(REPLACE "%AIR%" "false" c "${config}")
  file(WRITE ${WORK}/vacuum/config.resolved.toml "# cgdem abc123 resolved configuration of die.toml\n${c}")
  return()
endif()

string(REPLACE "%WORK%" "${WORK}" args "${ARGS}")
string(REPLACE "%OUT%" "${OUT}" args "${args}")
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${CGDEM} compare ${args} WORKING_DIRECTORY ${OUT} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
message("cgdem compare ${args}\nexit code ${rc}\nstdout:\n${out}\nstderr:\n${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "${EXPECT}")
  message(FATAL_ERROR "expected exit code 0 and stdout matching: ${EXPECT}")
endif()
string(REGEX MATCH "wrote ([^\n]*)/compare.md" _ "${out}")
set(dir ${CMAKE_MATCH_1})
if(NOT IS_ABSOLUTE "${dir}")
  set(dir ${OUT}/${dir})
endif()
foreach(f compare.md metrics_compare.csv curves_compare.csv curves_distance.csv runs_compare.csv)
  if(NOT EXISTS ${dir}/${f})
    message(FATAL_ERROR "missing ${dir}/${f}")
  endif()
endforeach()
file(READ ${dir}/compare.md md)
file(READ ${dir}/curves_compare.csv curves)
file(READ ${dir}/metrics_compare.csv metrics)
# The key difference, a NaN metric shown as missing, the carried-through columns with units.
foreach(re "\\| `air.enabled` \\| true \\| false \\|" "\\| p_B_peak_Pa \\| Pa \\| 15.5 \\| — \\| — \\| — \\|"
        "\\| fill_mass_kg \\| kg \\| 0.002 \\| 0.003 \\| \\+0.001 \\| \\+50 % \\|" "### mass_in_shoe \\(kg\\)"
        "### Q_cavity \\(m\\^3/s\\)")
  if(NOT md MATCHES "${re}")
    message(FATAL_ERROR "compare.md does not match ${re}")
  endif()
endforeach()
if(md MATCHES "nan")
  message(FATAL_ERROR "compare.md shows a NaN as a number")
endif()
foreach(re "t_s,[^\n]*:mass_in_die_kg,[^\n]*:transfer_rate_kg_s,[^\n]*:p_A_Pa,[^\n]*:mass_in_shoe_kg,[^\n]*:Q_cavity_m3_s"
        "\n0.1,0.1,0.2,")
  if(NOT curves MATCHES "${re}")
    message(FATAL_ERROR "curves_compare.csv does not match ${re}")
  endif()
endforeach()
if(NOT metrics MATCHES "\np_B_peak_Pa,Pa,15.5,,,\n")
  message(FATAL_ERROR "metrics_compare.csv: the NaN metric is not empty (missing)")
endif()
# Plots: drawn, or the report says why they were skipped.
if(EXISTS ${dir}/curves.png)
  if(NOT md MATCHES "!\\[[^]]*\\]\\(curves.png\\)" OR NOT EXISTS ${dir}/curves_extra.png)
    message(FATAL_ERROR "curves.png drawn but not in the report, or curves_extra.png missing")
  endif()
elseif(NOT md MATCHES "Plots skipped: ")
  message(FATAL_ERROR "no curves.png and the report does not say why")
endif()
