// The CSV files a run writes (energy.csv, diagnostics.csv, shoe_surface.csv, impacts.csv):
// one writer and one reader, so that every file describes itself the same way.
//
// Layout (self-describing; numpy.genfromtxt(f, names=True, comments="#", delimiter=","),
// numpy.loadtxt(f, skiprows=1, comments="#", delimiter=",") and pandas.read_csv(f,
// comment="#") all read it as is):
//
//   t_s,mass_in_die_kg,transfer_rate_kg_s,impacts       the column line, always first
//   # cgdem 1a2b3c4, case die.toml, ...                 provenance lines (revision, case)
//   # t_s: s, time                                      one line per column:
//   # mass_in_die_kg: kg, solid mass in the die         "# <name>: <unit>, <description>"
//   ...
//   0,0,0,0                                             the rows
//
// Units convention: every column name ends with its SI unit as suffix, written as the unit
// with '/' and ' ' replaced by '_' and '^' dropped: s, kg, m, Pa, J, kg_s (kg/s), m_s (m/s),
// m3 (m^3), m3_s (m^3/s), kg_m_s (kg m/s), as metrics.csv names its metrics. A
// dimensionless column (a count, an index: particles, removed, inside_walls, impacts,
// bubbles, bin, parcels, id; air_steps.csv's solver counts, flag and relative residual) has
// the unit "1" and no suffix; so has a text column (timings.csv's revision, group and phase,
// each described as "text: ..."). '#' lines may appear anywhere
// (every reader above skips them); a restarted run keeps the rows up to its restart time
// and continues the file.
#pragma once
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace cgdem::io {

struct CsvColumn {
  std::string name;         // quantity + "_" + unit_suffix(unit), or the quantity when unit == "1"
  std::string unit;         // SI unit as text ("kg/s", "m^3", "kg m/s"; "1": dimensionless)
  std::string description;  // one line
};
using CsvColumns = std::vector<CsvColumn>;

// "kg/s" -> "kg_s", "m^3/s" -> "m3_s", "kg m/s" -> "kg_m_s", "1" -> "" (no suffix).
std::string unit_suffix(const std::string& unit);
// The quantity a column holds: its name without the unit suffix ("p_A_Pa", "Pa" -> "p_A").
std::string quantity_name(const std::string& name, const std::string& unit);

// Throws cgdem::Error naming `what` and the column on an empty or duplicate name, a name with
// ',', '#', a quote or whitespace, an empty unit or description, a newline in either, or a
// name that does not end with its unit's suffix.
void check_columns(const CsvColumns& columns, const std::string& what);

// The column line, then "# <line>" for every provenance line, then the column descriptions
// (each line ends with '\n'). Checks the columns (check_columns).
std::string csv_preamble(const CsvColumns& columns, const std::vector<std::string>& provenance,
                         const std::string& what);

// A time series whose rows are written as the run goes (the first field of a row is its time).
class CsvSeries {
 public:
  // Fresh: writes `path` with the preamble. continue_after = t (a restart): an existing file
  // keeps its preamble and the rows up to time t (a torn last line and later rows dropped;
  // rewritten atomically), and new rows follow; its column line must be the columns' (else
  // cgdem::Error naming the file and both lines). A missing file is started fresh.
  CsvSeries(std::string path, CsvColumns columns, const std::vector<std::string>& provenance,
            std::optional<double> continue_after = std::nullopt);
  ~CsvSeries();
  CsvSeries(const CsvSeries&) = delete;
  CsvSeries& operator=(const CsvSeries&) = delete;

  // One row, its fields comma-separated, without the newline; cgdem::Error when it does not
  // have one field per column. Rows reach the operating system at flush().
  void row(const std::string& fields);
  // Several rows, each ending with '\n'.
  void rows(const std::string& lines);
  // One row from numbers (%.10g; non-finite ones as nan/inf).
  void numbers(const std::vector<double>& values);
  void flush();

  const std::string& path() const { return path_; }
  const CsvColumns& columns() const { return columns_; }

 private:
  void write_text(const std::string& text);
  std::string path_;
  CsvColumns columns_;
  std::FILE* file_ = nullptr;
};

// A whole file at once (preamble and `rows`, each ending with '\n'), written atomically.
void write_csv_file(const std::string& path, const CsvColumns& columns, const std::vector<std::string>& provenance,
                    const std::string& rows);

// A CSV file of numbers read into named columns. Reads this layout and the one written before
// it ('#' lines, then the column line with bare names: t, mass_in_die, p_A ...; such names
// get their unit suffix here, from the table of the old names, so that readers use the new
// names for both). Values that do not parse as numbers ("nan", empty) become NaN.
struct CsvTable {
  std::string source;                      // file name, for messages
  std::vector<std::string> names;          // as in the file (old names upgraded)
  std::vector<std::string> units;          // "" when not known
  std::vector<std::string> descriptions;   // "" when the file has none
  std::vector<std::string> comments;       // every '#' line, without "# "
  std::vector<std::vector<double>> columns;  // columns[c][row]
  bool self_describing = false;            // the file has a description line for every column

  size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
  // A column by its name or by its quantity (the name without the unit suffix: "t_s" or "t").
  bool has(const std::string& name) const;
  // The column, or throws cgdem::Error naming the file and listing the columns it has.
  const std::vector<double>& col(const std::string& name) const;
  // The column's index, or -1.
  long index(const std::string& name) const;
  std::string quantity(size_t c) const { return quantity_name(names[c], units[c]); }
  // The revision of "# cgdem <revision>[,] ..." (the first such line), "" when none.
  std::string revision() const;
};

// Throws cgdem::Error naming the file on a missing file, missing column line or a row with
// the wrong number of fields. A trailing incomplete line (a run still writing) is dropped.
CsvTable read_csv_table(const std::string& path);

// The unit of a column name as cgdem wrote it before the names carried their units
// ("t" -> "s", "p_A" -> "Pa", "impacts" -> "1"), "" when the name is not one of them.
std::string legacy_column_unit(const std::string& old_name);

}  // namespace cgdem::io
