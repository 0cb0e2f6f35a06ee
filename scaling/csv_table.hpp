// A CSV file of numbers read into named columns: the run outputs energy.csv and
// diagnostics.csv, in the layout of io/csv_series.hpp (the column line, '#' lines with the
// provenance and each column's unit and description, the rows) or the one before it ('#'
// lines, then bare names: t, mass_in_die ...; upgraded to the new names on reading).
// Columns are looked up by name ("t_s", "mass_in_die_kg") or by quantity ("t"), never by
// position. Values that do not parse as numbers ("nan", empty) become NaN.
#pragma once
#include "io/csv_series.hpp"

namespace cgdem::scaling {

using io::CsvTable;
using io::read_csv_table;

}  // namespace cgdem::scaling
