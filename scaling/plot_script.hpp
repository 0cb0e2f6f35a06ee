// Runs one of the Python plot scripts of scaling/ (plot_scale.py, plot_spectrum.py) on a
// report folder, with the first python3 that has matplotlib: $CGDEM_PYTHON, python3 on the
// PATH (which may be a virtual environment without it), then the system's /usr/bin/python3
// (Debian's python3-matplotlib). Plots are optional: every figure's data is in the CSV files.
#pragma once
#include <string>

namespace cgdem::scaling {

// Runs scaling/<script> <dir>. Returns "" when the script ran, else why no PNG was drawn
// (script missing, no python3 with matplotlib, or the command that failed).
std::string run_plot_script(const std::string& script, const std::string& dir);

}  // namespace cgdem::scaling
