// The CSV layout of the run outputs (io/csv_series.hpp): exact text (column line first, then
// provenance and one description line per column), the unit-suffix rule, row validation,
// continuation after a restart, and the reader on this layout and the one before it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "core/error.hpp"
#include "io/csv_series.hpp"
#include "scratch.hpp"

using namespace cgdem;
using namespace cgdem::io;
using namespace cgdem::io::test;

namespace {

const CsvColumns kCols = {{"t_s", "s", "time"},
                          {"mass_in_die_kg", "kg", "solid mass in the die"},
                          {"transfer_rate_kg_s", "kg/s", "rate, a backward difference"},
                          {"impacts", "1", "parcels at the floor so far"}};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(CsvSeries, UnitSuffixes) {
  EXPECT_EQ(unit_suffix("kg/s"), "kg_s");
  EXPECT_EQ(unit_suffix("m^3/s"), "m3_s");
  EXPECT_EQ(unit_suffix("kg m/s"), "kg_m_s");
  EXPECT_EQ(unit_suffix("1"), "");
  EXPECT_EQ(quantity_name("p_A_Pa", "Pa"), "p_A");
  EXPECT_EQ(quantity_name("Q_cavity_m3_s", "m^3/s"), "Q_cavity");
  EXPECT_EQ(quantity_name("impacts", "1"), "impacts");
  EXPECT_EQ(quantity_name("t_s", ""), "t_s");  // unit unknown: the name as it is
  // A name without its unit's suffix, a duplicate, an empty description: clear errors.
  EXPECT_NE(error_of([] { check_columns({{"t", "s", "time"}}, "x.csv"); }).find("x.csv: column 't' in s must end with '_s'"),
            std::string::npos);
  EXPECT_NE(error_of([] { check_columns({{"t_s", "s", "a"}, {"t_s", "s", "b"}}, "x.csv"); }).find("appears twice"),
            std::string::npos);
  EXPECT_NE(error_of([] { check_columns({{"t_s", "s", ""}}, "x.csv"); }).find("one non-empty line"), std::string::npos);
  EXPECT_NE(error_of([] { check_columns({{"a,b", "1", "x"}}, "x.csv"); }).find("bad column name 'a,b'"),
            std::string::npos);
  EXPECT_NE(error_of([] { check_columns({}, "x.csv"); }).find("no columns"), std::string::npos);
}

TEST(CsvSeries, ColumnLineFirstThenProvenanceAndDescriptions) {
  const std::string f = scratch_dir() + "/diagnostics.csv";
  const std::string head =
      "t_s,mass_in_die_kg,transfer_rate_kg_s,impacts\n"
      "# cgdem abc123, case die.toml\n"
      "# t_s: s, time\n"
      "# mass_in_die_kg: kg, solid mass in the die\n"
      "# transfer_rate_kg_s: kg/s, rate, a backward difference\n"
      "# impacts: 1, parcels at the floor so far\n";
  {
    CsvSeries s(f, kCols, {"cgdem abc123, case die.toml"});
    s.row("0,0,0,0");
    s.numbers({1e-3, 1.0 / 3.0, NAN, 2});
    s.flush();
    EXPECT_EQ(slurp(f), head + "0,0,0,0\n0.001,0.3333333333,nan,2\n");
    EXPECT_NE(error_of([&] { s.row("1,2,3"); }).find("a row of 3 fields for 4 columns"), std::string::npos);
    EXPECT_NE(error_of([&] { s.rows("1,2,3,4"); }).find("end with a newline"), std::string::npos);
  }
  const CsvTable t = read_csv_table(f);
  std::printf("read %zu columns, %zu rows, revision '%s', self-describing %d\n", t.names.size(), t.rows(),
              t.revision().c_str(), int(t.self_describing));
  EXPECT_TRUE(t.self_describing);
  EXPECT_EQ(t.revision(), "abc123");
  EXPECT_EQ(t.names, (std::vector<std::string>{"t_s", "mass_in_die_kg", "transfer_rate_kg_s", "impacts"}));
  EXPECT_EQ(t.units, (std::vector<std::string>{"s", "kg", "kg/s", "1"}));
  EXPECT_EQ(t.descriptions[2], "rate, a backward difference");
  EXPECT_EQ(t.col("mass_in_die").at(1), 0.3333333333);  // by quantity ...
  EXPECT_EQ(&t.col("mass_in_die_kg"), &t.col("mass_in_die"));  // ... or by name
  EXPECT_TRUE(std::isnan(t.col("transfer_rate_kg_s").at(1)));
  EXPECT_NE(error_of([&] { t.col("p_A"); }).find("no column 'p_A' (it has: t_s, mass_in_die_kg"), std::string::npos);
}

TEST(CsvSeries, ContinuesAfterARestart) {
  const std::string f = scratch_dir() + "/energy.csv";
  {
    CsvSeries s(f, kCols, {"cgdem abc123, case die.toml"});
    for (int i = 0; i < 4; ++i) s.numbers({0.1 * i, 1.0 * i, 0, double(i)});
  }
  const std::string uninterrupted = slurp(f);
  spit(f, uninterrupted + "0.4,4.");  // a crash tore the last line
  {
    CsvSeries s(f, kCols, {"cgdem def456, case die.toml"}, 0.1);  // continued from t = 0.1 s
    s.numbers({0.2, 2.0, 0, 2});
    s.numbers({0.3, 3.0, 0, 3});
  }
  const std::string text = slurp(f);
  std::printf("after the restart:\n%s", text.c_str());
  EXPECT_EQ(text, uninterrupted);  // as if the run had never stopped
  const CsvTable t = read_csv_table(f);
  EXPECT_EQ(t.rows(), 4u);
  EXPECT_EQ(t.revision(), "abc123");
  // Other columns: refused, the file untouched.
  const std::string msg = error_of([&] { CsvSeries(f, {{"t_s", "s", "time"}}, {}, 0.1); });
  EXPECT_NE(msg.find("energy.csv: cannot continue it, its columns are 't_s,mass_in_die_kg"), std::string::npos) << msg;
  EXPECT_EQ(slurp(f), text);
  // A file of the old layout cannot be continued either.
  spit(f, "# cgdem abc123, case die.toml\nt,mass_in_die\n0,0\n");
  EXPECT_NE(error_of([&] { CsvSeries(f, kCols, {}, 0.0); }).find("its columns are 't,mass_in_die'"), std::string::npos);
  // A missing file starts fresh.
  const std::string g = scratch_dir() + "/fresh.csv";
  { CsvSeries s(g, {{"t_s", "s", "time"}}, {}, 0.5); }
  EXPECT_EQ(slurp(g), "t_s\n# t_s: s, time\n");
  EXPECT_THROW(CsvSeries(scratch_dir() + "/no_dir/x.csv", kCols, {}), Error);
}

TEST(CsvSeries, ReadsTheLayoutBeforeUnitsWithTheNewNames) {
  const std::string f = scratch_dir() + "/diagnostics.csv";
  spit(f, "# cgdem 0ld0ld0, case die.toml\nt,mass_in_die,transfer_rate,impacts,p_A,Q_cavity,V_bubbles,foo\n"
          "0,1,2,3,4,5,6,7\n0.1,1,2,3,nan,5,6,7\n0.2,1");  // a row still being written
  const CsvTable t = read_csv_table(f);
  std::printf("old names read as:");
  for (size_t c = 0; c < t.names.size(); ++c) std::printf(" %s [%s]", t.names[c].c_str(), t.units[c].c_str());
  std::printf("\n");
  EXPECT_FALSE(t.self_describing);
  EXPECT_EQ(t.names, (std::vector<std::string>{"t_s", "mass_in_die_kg", "transfer_rate_kg_s", "impacts", "p_A_Pa",
                                               "Q_cavity_m3_s", "V_bubbles_m3", "foo"}));
  EXPECT_EQ(t.quantity(4), "p_A");
  EXPECT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.revision(), "0ld0ld0");
  EXPECT_EQ(t.col("t").at(1), 0.1);
  EXPECT_EQ(t.col("t_s").at(1), 0.1);
  EXPECT_TRUE(std::isnan(t.col("p_A_Pa").at(1)));
  spit(f, "t,a\n0,1,2\n");
  EXPECT_NE(error_of([&] { read_csv_table(f); }).find("line 2: 3 fields, the column line has 2"), std::string::npos);
  spit(f, "# only comments\n");
  EXPECT_NE(error_of([&] { read_csv_table(f); }).find("no column line"), std::string::npos);
  EXPECT_NE(error_of([&] { read_csv_table(f + ".absent"); }).find("cannot read"), std::string::npos);
}

TEST(CsvSeries, WholeFileAtOnce) {
  const std::string f = scratch_dir() + "/impacts.csv";
  write_csv_file(f, {{"id", "1", "parcel id"}, {"t_s", "s", "time"}}, {"cgdem abc123"}, "7,0.5\n8,0.25\n");
  EXPECT_EQ(slurp(f), "id,t_s\n# cgdem abc123\n# id: 1, parcel id\n# t_s: s, time\n7,0.5\n8,0.25\n");
}
