// Messages of the case reader (core/config.hpp): every error names the file and line, or
// the command-line option for a --set value; unknown keys get "did you mean"; syntax
// errors name their line; an integer beyond 64 bits and a value beyond its bound are
// errors that state what was expected.
#include <gtest/gtest.h>

#include <string>

#include "core/config.hpp"
#include "core/error.hpp"

using namespace cgdem;

namespace {

const char* kCase =
    "[contact]\n"           // 1
    "stiffness = 50.0\n"    // 2
    "restitution = 1.5\n"   // 3
    "friction = 0.3\n"      // 4
    "\n"                    // 5
    "[output]\n"            // 6
    "energy_intervall = 1e-4\n"  // 7
    "count = 9999999999999999999\n";  // 8

// The message of the ConfigError `fn` throws (fails the test if it throws nothing).
template <class Fn>
std::string message_of(Fn&& fn) {
  try {
    fn();
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError";
  return "";
}

}  // namespace

TEST(ConfigMessages, NamesFileLineKeyAndBound) {
  Config cfg = Config::from_string(kCase, "case.toml");
  const std::string m = message_of([&] { cfg.root().section("contact").number("restitution", Range::open_closed(0, 1)); });
  EXPECT_EQ(m, "case.toml:3: key 'contact.restitution': expected a number in (0, 1], got 1.5");
}

TEST(ConfigMessages, MissingKeyNamesItsTable) {
  Config cfg = Config::from_string(kCase, "case.toml");
  const std::string m = message_of([&] { cfg.root().section("output").number("dt"); });
  EXPECT_EQ(m.rfind("case.toml:6: key 'output.dt': missing", 0), 0u) << m;
}

TEST(ConfigMessages, SetValueIsTheCommandLines) {
  Config cfg = Config::from_string(kCase, "case.toml");
  cfg.apply_override("contact.friction=-1");
  const std::string m = message_of([&] { cfg.root().section("contact").number("friction", Range::closed(0, 5)); });
  EXPECT_EQ(m, "command line (--set 'contact.friction=-1'): key 'contact.friction': expected a number in [0, 5], got -1");
  EXPECT_EQ(m.find("case.toml"), std::string::npos) << m;
}

TEST(ConfigMessages, SaturatedIntegerIsRefused) {
  Config cfg = Config::from_string(kCase, "case.toml");
  const std::string m = message_of([&] { cfg.root().section("output").integer("count"); });
  EXPECT_NE(m.find("case.toml:8: key 'output.count': the integer 9999999999999999999 does not fit in 64 bits"),
            std::string::npos)
      << m;
}

TEST(ConfigMessages, UnknownKeysAtTheirLinesWithDidYouMean) {
  Config cfg = Config::from_string(kCase, "case.toml");
  Section out = cfg.root().section("output");
  out.number_or("energy_interval", 1e-3, Range::positive());
  Section contact = cfg.root().section("contact");
  contact.number("stiffness"), contact.number("friction"), contact.number_or("restitution", 0.9);
  const std::string m = message_of([&] { cfg.check_unused(); });
  EXPECT_NE(m.find("case.toml:7: unknown key 'output.energy_intervall' (did you mean 'output.energy_interval'?)"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("case.toml:8: unknown key 'output.count'"), std::string::npos) << m;  // no close name
}

TEST(ConfigMessages, SyntaxErrorNamesTheLine) {
  const std::string m = message_of([] { Config::from_string("[a]\nx = 1\nx = 2\n", "dup.toml"); });
  EXPECT_EQ(m.rfind("dup.toml:3: cannot read the case file: syntax error: value (\"x\") already exists", 0), 0u) << m;
  const std::string t = message_of([] { Config::from_string("[a]\nx = \n", "cut.toml"); });
  EXPECT_EQ(t.rfind("cut.toml:2: cannot read the case file: syntax error:", 0), 0u) << t;
}

TEST(ConfigMessages, BadSetPathIsAnError) {
  Config cfg = Config::from_string(kCase, "case.toml");
  EXPECT_THROW(cfg.apply_override("a[x].b=1"), ConfigError);
  EXPECT_THROW(cfg.apply_override("a..b=1"), ConfigError);
  EXPECT_THROW(cfg.apply_override("a.=1"), ConfigError);
}
