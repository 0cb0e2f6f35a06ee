// ParticleTable: the plain exchange format between the particle storage and files
// (initial conditions from CSV, snapshots and checkpoints in HDF5). Structure of arrays,
// SI units: x [m], v [m/s], omega [rad/s], d [m] (diameter of the coarse-grained
// parcel as simulated). id and species have one entry per particle; v and omega are
// either empty ("not given") or one entry per particle.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/vec3.hpp"

namespace cgdem::io {

struct ParticleTable {
  std::vector<int64_t> id;
  std::vector<int> species;
  std::vector<Vec3> x, v, omega;
  std::vector<double> d;

  size_t size() const { return x.size(); }
  bool has_velocity() const { return !v.empty(); }
  bool has_omega() const { return !omega.empty(); }

  // Throws cgdem::Error naming the inconsistent array (`context`, e.g. a file name,
  // is prefixed to the message).
  void validate(const std::string& context = "particle table") const {
    const size_t n = size();
    auto check = [&](size_t m, const char* name, bool may_be_empty) {
      if (m == n || (may_be_empty && m == 0)) return;
      throw Error(context + ": '" + name + "' has " + std::to_string(m) + " entries but 'x' has " +
                  std::to_string(n) + (may_be_empty ? " (it must have as many or none)" : ""));
    };
    check(id.size(), "id", false);
    check(species.size(), "species", false);
    check(d.size(), "d", false);
    check(v.size(), "v", true);
    check(omega.size(), "omega", true);
  }
};

}  // namespace cgdem::io
