// metrics.csv: the scalar results of a run (one `name,value` row each), written once at
// the end of a run into its output folder. It is what `cgdem converge` and `cgdem scale`
// read, so a metric's name is its contract: snake_case with the SI unit as suffix where
// it has one (front_time_s, fill_mass_kg). Non-finite values are written as "nan".
//
// "Not computed": a metric that a run cannot compute is left out of its file rather than
// written as NaN (app/run_metrics.hpp: the pressure and bubble metrics of a run without air,
// the windowed peaks of a run that ends before the die opens). NaN keeps its meaning of a
// computed "did not happen" (front_time_s of a front that never reached the floor).
// Readers comparing runs show a metric missing from one of them as "not computed".
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace cgdem::io {

using Metrics = std::vector<std::pair<std::string, double>>;

// Writes `path` atomically. Throws cgdem::Error on an invalid name (empty, or containing
// ',', whitespace or a newline) or an I/O failure.
void write_metrics(const std::string& path, const Metrics& m);

// Reads a file written by write_metrics ('#' comment lines are skipped). Throws
// cgdem::Error naming the file and line on a malformed row or a missing header.
Metrics read_metrics(const std::string& path);

// The value of `name`, or throws cgdem::Error listing the names the file has.
double metric(const Metrics& m, const std::string& name, const std::string& source);

// Whether the file holds `name`.
bool has_metric(const Metrics& m, const std::string& name);

// Whether `name` is one of the metrics cgdem run leaves out when it cannot compute them
// (above): p_<cell>_peak_Pa, p_<cell>_peak_time_s, p_<cell>_mean_Pa, bubble_*_peak_m3 /
// _time_s, transfer_rate_peak_kg_s / _time_s. A reader missing one of these reports "not
// computed"; any other missing name is an error (a misspelt metric, say).
bool may_be_left_out(const std::string& name);

}  // namespace cgdem::io
