// The run driver (solvers/run/run_driver.hpp) calls a run's phases in its one order: set-up,
// health, the starting state's outputs (not on a restart), then per step: step, observe,
// due, health when due, outputs, progress; the report last, whose status it returns.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "solvers/run/run_driver.hpp"

namespace {

// A run of `steps` steps that records its phases; health is due after the steps listed.
class Recorder final : public cgdem::run::Run {
 public:
  Recorder(bool restart, int steps, std::vector<int> health_after) : restart_(restart), steps_(steps),
                                                                    health_after_(std::move(health_after)) {}
  bool set_up() override { return log("set_up"), restart_; }
  void check_health() override { log("health"); }
  void write_initial() override { log("initial"); }
  bool finished() const override { return n_ >= steps_; }
  void step() override { ++n_, log("step"); }
  void observe() override { log("observe"); }
  cgdem::run::Due due() override {
    log("due");
    cgdem::run::Due d;
    for (int k : health_after_) d.health = d.health || k == n_;
    d.last = n_ == steps_;
    return d;
  }
  void write_due() override { log("write"); }
  void progress(bool last) override { log(last ? "progress(last)" : "progress"); }
  int report() override { return log("report"), 7; }
  std::string sequence() const {
    std::string s;
    for (const auto& e : log_) s += (s.empty() ? "" : " ") + e;
    return s;
  }

 private:
  void log(const std::string& what) { log_.push_back(what); }
  bool restart_;
  int steps_, n_ = 0;
  std::vector<int> health_after_;
  std::vector<std::string> log_;
};

TEST(RunDriver, CallsThePhasesInTheirOrder) {
  Recorder r(false, 2, {2});
  EXPECT_EQ(cgdem::run::drive(r), 7);
  EXPECT_EQ(r.sequence(),
            "set_up health initial step observe due write progress step observe due health write progress(last) report");
}

TEST(RunDriver, ARestartWritesNoStartingOutputs) {
  Recorder r(true, 1, {});
  cgdem::run::drive(r);
  EXPECT_EQ(r.sequence(), "set_up health step observe due write progress(last) report");
}

TEST(RunDriver, ARunAlreadyAtItsEndOnlyReports) {
  Recorder r(true, 0, {});
  cgdem::run::drive(r);
  EXPECT_EQ(r.sequence(), "set_up health report");
}

}  // namespace
