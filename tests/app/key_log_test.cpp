// Config::log_keys (core/config.hpp): every accessor notes its key once, with the type,
// default and allowed values it validates; array elements as [], the first use kept.
#include <gtest/gtest.h>

#include "core/config.hpp"

using namespace cgdem;

namespace {

TEST(KeyLog, NotesWhatTheAccessorsValidate) {
  Config cfg = Config::from_string(R"(
[a]
x = 2.0
[[a.item]]
name = "first"
[[a.item]]
name = "second"
)");
  KeyLog log;
  cfg.log_keys(&log);
  Section a = cfg.root().section("a");
  a.number("x", Range::open_closed(0, 10));
  a.integer_or("n", 3, Range::closed(1, 5));
  a.string_or("mode", "fast", {"fast", "slow"});
  a.vec3_or("at", {1, 2, 3});
  a.boolean_or("on", true);
  for (const Section& s : a.sections("item")) s.string("name");
  a.number_or("x", 1.0);  // read again: the first use stays
  const auto& u = log.uses();
  ASSERT_EQ(u.size(), 6u);
  EXPECT_EQ(u[0].path, "a.x");
  EXPECT_EQ(u[0].type, "number");
  EXPECT_EQ(u[0].default_value, "");
  EXPECT_EQ(u[0].allowed, "in (0, 10]");
  EXPECT_EQ(u[1].path, "a.n");
  EXPECT_EQ(u[1].type, "integer");
  EXPECT_EQ(u[1].default_value, "3");
  EXPECT_EQ(u[1].allowed, "in [1, 5]");
  EXPECT_EQ(u[2].default_value, "\"fast\"");
  EXPECT_EQ(u[2].allowed, "one of \"fast\", \"slow\"");
  EXPECT_EQ(u[3].type, "[x, y, z]");
  EXPECT_EQ(u[3].default_value, "[1, 2, 3]");
  EXPECT_EQ(u[4].default_value, "true");
  EXPECT_EQ(u[5].path, "a.item[].name");
}

TEST(KeyLog, NothingIsNotedWithoutALog) {
  Config cfg = Config::from_string("[a]\nx = 1.0\n");
  KeyLog log;
  cfg.root().section("a").number("x");
  EXPECT_TRUE(log.uses().empty());
}

}  // namespace
