// metrics.csv: the scalar results of a run (one `name,value` row each), written once at
// the end of a run into its output folder. It is what `cgdem converge` and `cgdem scale`
// read, so a metric's name is its contract: snake_case with the SI unit as suffix where
// it has one (front_time_s, fill_mass_kg). Non-finite values are written as "nan".
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace cgdem::io {

using Metrics = std::vector<std::pair<std::string, double>>;

// Writes `path` atomically. Throws cgdem::Error on an invalid name (empty, or containing
// ',', whitespace or a newline) or an I/O failure.
void write_metrics(const std::string& path, const Metrics& m);

// Reads a file written by write_metrics. Throws cgdem::Error naming the file and line on
// a malformed row or a missing header.
Metrics read_metrics(const std::string& path);

// The value of `name`, or throws cgdem::Error listing the names the file has.
double metric(const Metrics& m, const std::string& name, const std::string& source);

}  // namespace cgdem::io
