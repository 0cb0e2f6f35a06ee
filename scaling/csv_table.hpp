// A CSV file of numbers read into named columns: the run outputs energy.csv and
// diagnostics.csv ('#' comment lines, then one header line, then rows). Columns are looked
// up by name, never by position (app/energy_csv.hpp). Values that do not parse as numbers
// ("nan", empty) become NaN.
#pragma once
#include <string>
#include <vector>

namespace cgdem::scaling {

struct CsvTable {
  std::string source;  // file name, for messages
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  // columns[c][row]

  size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
  bool has(const std::string& name) const;
  // The column, or throws cgdem::Error naming the file and listing the columns it has.
  const std::vector<double>& col(const std::string& name) const;
};

// Throws cgdem::Error naming the file on a missing file, missing header or a row with the
// wrong number of fields. A trailing incomplete line (a run still writing) is dropped.
CsvTable read_csv_table(const std::string& path);

}  // namespace cgdem::scaling
