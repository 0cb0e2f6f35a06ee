// Agreement thresholds of `cgdem scale`, one per kind of comparison, with their defaults
// and the reason for each (docs/scaling.md). `--threshold name=value` overrides one.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace cgdem::scaling {

struct ThresholdInfo {
  std::string name;
  double value;
  std::string meaning;
};

// Defaults, in the order they are documented.
const std::vector<ThresholdInfo>& default_thresholds();

class Thresholds {
 public:
  Thresholds();
  // "name=value"; throws cgdem::Error naming --threshold and the known names.
  void set(const std::string& assignment);
  double operator[](const std::string& name) const;  // throws on an unknown name
  const std::map<std::string, double>& all() const { return v_; }

 private:
  std::map<std::string, double> v_;
};

}  // namespace cgdem::scaling
