#include "scaling/thresholds.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "core/error.hpp"

namespace cgdem::scaling {

const std::vector<ThresholdInfo>& default_thresholds() {
  static const std::vector<ThresholdInfo> t{
      {"energy", 0.05, "max |e_l - e_1| over time / S_E (energies per unit mass)"},
      {"momentum", 0.05, "max |v_l - v_1| over time / sqrt(2 S_E) (centre-of-mass velocity)"},
      {"rotation", 0.30, "max |e_rot,l - e_rot,1| over time / its peak at l = 1"},
      {"closure", 0.02, "max |budget closure| over time / S_E, every run"},
      {"scalar", 0.10, "|x_l - x_1| / |x_1| for scalar observables"},
      {"time", 0.05, "|t_l - t_1| / (time.end - time.start) for event times"},
      {"curve", 0.25, "normalized L2 distance of a time curve (transfer rate, pressure)"},
      {"profile", 0.15, "normalized L2 distance of the final pile-height profile"},
      {"spectrum", 0.10, "max over the leading modes of |energy fraction_l - energy fraction_1| (POD)"},
      {"angle", 30.0, "largest principal angle between the leading POD subspaces, degrees"},
  };
  return t;
}

Thresholds::Thresholds() {
  for (const auto& t : default_thresholds()) v_[t.name] = t.value;
}

void Thresholds::set(const std::string& a) {
  const auto eq = a.find('=');
  std::string names;
  for (const auto& [n, v] : v_) names += (names.empty() ? "" : ", ") + n;
  if (eq == std::string::npos || eq == 0)
    throw Error(fmt::format("--threshold '{}': expected name=value (names: {})", a, names));
  const std::string name = a.substr(0, eq), value = a.substr(eq + 1);
  if (!v_.count(name)) throw Error(fmt::format("--threshold '{}': unknown name '{}' (names: {})", a, name, names));
  char* end = nullptr;
  const double x = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(x) || !(x > 0))
    throw Error(fmt::format("--threshold '{}': the value must be a positive number", a));
  v_[name] = x;
}

double Thresholds::operator[](const std::string& name) const {
  auto it = v_.find(name);
  if (it == v_.end()) throw Error("internal: unknown threshold " + name);
  return it->second;
}

}  // namespace cgdem::scaling
