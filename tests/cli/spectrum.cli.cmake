# `cgdem spectrum` end to end on synthetic run folders (tests/cli/spectrum_data/spectrum_check.cmake
# writes them): the printed dominant frequencies of known sines, and every bad input as a
# clear error.
function(spectrum_cli_test name expect fail)
  add_test(NAME cli.spectrum.${name}
           COMMAND ${CMAKE_COMMAND} -DCGDEM=$<TARGET_FILE:cgdem> -DWORK=${PROJECT_BINARY_DIR}/cli_out/spectrum_${name}
                   "-DARGS=${ARGN}" "-DEXPECT=${expect}" -DFAIL=${fail}
                   -P ${PROJECT_SOURCE_DIR}/tests/cli/spectrum_data/spectrum_check.cmake)
  set_tests_properties(cli.spectrum.${name} PROPERTIES LABELS cli)
endfunction()

# Sines at 625, 156.25 and 468.75 Hz sampled at 5 kHz; 64-sample segments (df = 78.125 Hz)
# put each on a bin (8, 2, 6): the printed dominant frequency is exact. The default segment
# for 512 samples at 50 % overlap is 64 too (15 segments); --segment 0.0128s gives the same
# length. Peaks are sought from bin 3 with the Hann window and from bin 2 with rect
# (scaling/spectrum.hpp, lowest_peak_bin): B's 156.25 Hz is "no significant peak" with Hann.
set(dominant "A: dominant 625 Hz.*B: dominant 156.25 Hz.*C: dominant 468.75 Hz")
set(dominant_hann "A: dominant 625 Hz.*B: no significant peak.*C: dominant 468.75 Hz")
spectrum_cli_test(dominant_frequencies "15 segment\\(s\\) of 64 \\(df = 78.125 Hz.*${dominant_hann}" OFF %WORK%/run)
spectrum_cli_test(segment_in_seconds "${dominant}" OFF %WORK%/run --segment 0.0128s --window rect --overlap 0 --no-plot)
spectrum_cli_test(overlay_two_runs "first: .*${dominant_hann}.*second: .*${dominant_hann}" OFF
                  %WORK%/run %WORK%/run --labels first,second --cells A,B,C --output %WORK%/overlay --no-plot)
spectrum_cli_test(resampled_jitter "dominant 625 Hz" OFF %WORK%/jitter --dt 2e-4 --cells A --no-plot)

spectrum_cli_test(missing_folder "run folder '.*/absent' does not exist" ON %WORK%/absent)
spectrum_cli_test(no_pressure_columns "no pressure column \\(p_<cell>\\)" ON %WORK%/nop)
spectrum_cli_test(too_few_samples "--segment: 1024 samples .* longer than the 512 samples" ON %WORK%/run --segment 1024)
spectrum_cli_test(non_uniform "sampling is not uniform: t = 0.06 -> 0.0603 s" ON %WORK%/jitter)
spectrum_cli_test(unknown_window "--window: unknown window 'hamming'" ON %WORK%/run --window hamming)
spectrum_cli_test(several_runs_need_output "--output: several runs" ON %WORK%/run %WORK%/run)
