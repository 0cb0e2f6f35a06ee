#include "core/timers.hpp"

#include <fmt/format.h>

namespace cgdem {

int PhaseTimers::id(const std::string& name) {
  for (size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return static_cast<int>(i);
  names_.push_back(name);
  seconds_.push_back(0.0);
  calls_.push_back(0);
  return static_cast<int>(names_.size() - 1);
}

double PhaseTimers::seconds(const std::string& name) const {
  for (size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return seconds_[i];
  return 0.0;
}

double PhaseTimers::total() const {
  double s = 0;
  for (double x : seconds_) s += x;
  return s;
}

std::vector<PhaseTimers::Entry> PhaseTimers::entries() const {
  std::vector<Entry> out;
  for (size_t i = 0; i < names_.size(); ++i) out.push_back({names_[i], seconds_[i], calls_[i]});
  return out;
}

std::string PhaseTimers::table(const std::string& title) const {
  double tot = total();
  std::string out = fmt::format("{}\n  {:<22} {:>10} {:>10} {:>7}\n", title, "phase", "seconds", "calls", "%");
  for (size_t i = 0; i < names_.size(); ++i)
    out += fmt::format("  {:<22} {:>10.3f} {:>10} {:>6.1f}%\n", names_[i], seconds_[i], calls_[i],
                       tot > 0 ? 100.0 * seconds_[i] / tot : 0.0);
  out += fmt::format("  {:<22} {:>10.3f}\n", "total", tot);
  return out;
}

void PhaseTimers::reset() {
  for (auto& s : seconds_) s = 0;
  for (auto& c : calls_) c = 0;
}

}  // namespace cgdem
