// CsvSeries: exact text layout, row validation, append on restart (column check, cut of a
// torn last line, fresh start when the file is missing).
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "io/csv_series.hpp"
#include "scratch.hpp"

using namespace cgdem;
using namespace cgdem::io;
using namespace cgdem::io::test;

TEST(CsvSeries, WritesHeaderCommentsAndRows) {
  const std::string f = scratch_dir() + "/energy.csv";
  {
    CsvSeries s(f, {"t", "E_kin", "E_pot"}, {"revision abc123", "[dem]\ndt = 1e-6"});
    s.row({0.0, 1.0 / 3.0, -2.5e-12});
    s.flush();
    EXPECT_EQ(slurp(f), "# revision abc123\n# [dem]\n# dt = 1e-6\nt,E_kin,E_pot\n0,0.3333333333,-2.5e-12\n");
    s.row({1e-3, 12345678901.0, 0.1});
    EXPECT_THROW(s.row({1.0, 2.0}), Error);
  }  // destructor flushes
  EXPECT_EQ(slurp(f),
            "# revision abc123\n# [dem]\n# dt = 1e-6\nt,E_kin,E_pot\n0,0.3333333333,-2.5e-12\n"
            "0.001,1.23456789e+10,0.1\n");
  EXPECT_THROW(CsvSeries(f, {"a", "b,c"}), Error);
  EXPECT_THROW(CsvSeries(f, {}), Error);
}

TEST(CsvSeries, AppendContinuesAfterRestart) {
  const std::string dir = scratch_dir(), f = dir + "/fill.csv";
  {
    CsvSeries s(f, {"t", "m"}, {"run 1"});
    s.row({0.0, 0.0});
    s.row({0.1, 2.0});
  }
  spit(f, slurp(f) + "0.2,4.");  // a crash tore the last line
  {
    CsvSeries s(f, {"t", "m"}, {"restart from t = 0.1"}, /*append=*/true);
    s.row({0.2, 4.5});
  }
  EXPECT_EQ(slurp(f), "# run 1\nt,m\n0,0\n0.1,2\n# restart from t = 0.1\n0.2,4.5\n");
  try {
    CsvSeries s(f, {"t", "mass"}, {}, true);
    FAIL() << "appending with other columns must fail";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fill.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'t,m'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(f), "# run 1\nt,m\n0,0\n0.1,2\n# restart from t = 0.1\n0.2,4.5\n");  // untouched
  {
    CsvSeries s(dir + "/new.csv", {"t"}, {}, true);  // missing file: starts fresh
    s.row({1.0});
  }
  EXPECT_EQ(slurp(dir + "/new.csv"), "t\n1\n");
  EXPECT_THROW(CsvSeries(dir + "/no_dir/x.csv", {"t"}), Error);
}
