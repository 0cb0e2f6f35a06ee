// Runs one of the Python plot scripts of scaling/ (plot_scale.py, plot_spectrum.py,
// plot_compare.py) on a report folder, with the first python3 that has matplotlib: $CGDEM_PYTHON, python3 on the
// PATH (which may be a virtual environment without it), then the system's /usr/bin/python3
// (Debian's python3-matplotlib). Plots are optional: every figure's data is in the CSV files.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace cgdem::scaling {

// Where the scripts are looked for, in this order: $CGDEM_SCRIPT_DIR; PREFIX/share/cgdem/scripts
// beside an installed PREFIX/bin/cgdem (`cmake --install`); BUILD/share/cgdem/scripts beside
// the executable in a build tree, where CMake copies scaling/*.py at configure time. Nothing
// is found through the source tree, so a moved or installed binary behaves the same.
std::vector<std::filesystem::path> plot_script_dirs();

// Runs <script> <dir> from the first of plot_script_dirs() that has it. Returns "" when the
// script ran, else why no PNG was drawn (script missing, with the folders tried; no python3
// with matplotlib; or the command that failed).
std::string run_plot_script(const std::string& script, const std::string& dir);

}  // namespace cgdem::scaling
