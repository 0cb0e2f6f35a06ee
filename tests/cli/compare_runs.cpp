// compare_runs RUN_A RUN_B [--at T] [--rel-tol R] [--momentum-scale P] [--pos-tol X]
//
// Compares two runs of the same case (tests/cli/mpi_run.cmake: a run over MPI ranks
// against the single-process run, and restarts on other rank counts):
//   * the first row of energy.csv at or after time T (default: the last row): particles and removed
//     exactly, the solid mass to 1e-12, every energy column to R relative to the energy
//     scale (the largest |value| among both rows' energy columns) and every momentum
//     column to R of the momentum scale (P [kg m/s] when given, else the largest |value|
//     among both rows' momentum columns: of a bed nearly at rest that is noise itself);
//   * with X > 0, the end states in last_good.h5: the parcels by id, the largest
//     |x_A - x_B| against X [m].
// Prints every difference; exits 1 when one is out of tolerance, 2 on unreadable input.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/particle_h5.hpp"

namespace {

struct Row {
  std::vector<std::string> names;
  std::vector<double> values;
};

// The first row at or after time `at`, or the last row when at < 0.
Row row_at(const std::string& path, double at) {
  std::ifstream in(path);
  if (!in) throw cgdem::Error("cannot read " + path);
  Row r;
  std::string line, last;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (r.names.empty()) {
      std::stringstream s(line);
      for (std::string f; std::getline(s, f, ',');) r.names.push_back(f);
      continue;
    }
    if (at < 0 || std::strtod(line.c_str(), nullptr) >= at - 1e-12) {
      last = line;
      if (at >= 0) break;
    }
  }
  std::stringstream s(last);
  for (std::string f; std::getline(s, f, ',');) r.values.push_back(std::strtod(f.c_str(), nullptr));
  if (r.values.size() != r.names.size()) throw cgdem::Error(path + ": no complete data row");
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    fmt::print(stderr, "usage: compare_runs RUN_A RUN_B [--rel-tol R] [--pos-tol X]\n");
    return 2;
  }
  const std::string a = argv[1], b = argv[2];
  double rel_tol = 1e-6, pos_tol = 0, at = -1, momentum_scale = 0;
  for (int k = 3; k + 1 < argc; k += 2) {
    const std::string opt = argv[k];
    if (opt == "--rel-tol") rel_tol = std::atof(argv[k + 1]);
    else if (opt == "--pos-tol") pos_tol = std::atof(argv[k + 1]);
    else if (opt == "--at") at = std::atof(argv[k + 1]);
    else if (opt == "--momentum-scale") momentum_scale = std::atof(argv[k + 1]);
    else return fmt::print(stderr, "compare_runs: unknown option {}\n", opt), 2;
  }
  try {
    const Row ra = row_at(a + "/energy.csv", at), rb = row_at(b + "/energy.csv", at);
    if (ra.names != rb.names) throw cgdem::Error("the energy.csv columns differ");
    bool ok = true;
    auto col = [&](const Row& r, const std::string& n) {
      return r.values[std::find(r.names.begin(), r.names.end(), n) - r.names.begin()];
    };
    for (const char* exact : {"particles", "removed", "t_s"}) {
      const double x = col(ra, exact), y = col(rb, exact);
      const bool same = exact == std::string("t_s") ? std::fabs(x - y) <= 1e-12 * std::fabs(x) : x == y;
      fmt::print("{:>16}: {:.10g} vs {:.10g}{}\n", exact, x, y, same ? "" : "  <-- differs");
      ok = ok && same;
    }
    {
      const double x = col(ra, "mass_kg"), y = col(rb, "mass_kg"), d = std::fabs(x - y) / std::fabs(x);
      fmt::print("{:>16}: relative difference {:.3e} (tol 1e-12)\n", "mass_kg", d);
      ok = ok && d <= 1e-12;
    }
    double e_scale = 0, p_scale = 0;
    for (size_t c = 0; c < ra.names.size(); ++c) {
      const std::string& n = ra.names[c];
      const bool momentum = n == "px_kg_m_s" || n == "py_kg_m_s" || n == "pz_kg_m_s";
      double& s = momentum ? p_scale : e_scale;
      if (n[0] == 'E' || n[0] == 'W' || momentum) s = std::max({s, std::fabs(ra.values[c]), std::fabs(rb.values[c])});
    }
    if (momentum_scale > 0) p_scale = momentum_scale;
    for (size_t c = 0; c < ra.names.size(); ++c) {
      const std::string& n = ra.names[c];
      const bool momentum = n == "px_kg_m_s" || n == "py_kg_m_s" || n == "pz_kg_m_s";
      if (!(n[0] == 'E' || n[0] == 'W' || momentum)) continue;
      const double scale = momentum ? p_scale : e_scale;
      const double d = scale > 0 ? std::fabs(ra.values[c] - rb.values[c]) / scale : 0.0;
      fmt::print("{:>16}: {:.10g} vs {:.10g}, difference {:.3e} of the {} scale (tol {:g})\n", n, ra.values[c],
                 rb.values[c], d, momentum ? "momentum" : "energy", rel_tol);
      ok = ok && d <= rel_tol;
    }
    if (!(pos_tol > 0)) {
      fmt::print("{}\n", ok ? "runs agree" : "RUNS DIFFER");
      return ok ? 0 : 1;
    }
    const cgdem::io::ParticleTable pa = cgdem::io::read_particles_h5(a + "/last_good.h5");
    const cgdem::io::ParticleTable pb = cgdem::io::read_particles_h5(b + "/last_good.h5");
    std::map<int64_t, size_t> at;
    for (size_t i = 0; i < pb.size(); ++i) at[pb.id[i]] = i;
    double dx = 0;
    long missing = 0;
    for (size_t i = 0; i < pa.size(); ++i) {
      const auto it = at.find(pa.id[i]);
      if (it == at.end()) {
        ++missing;
        continue;
      }
      const auto& x = pa.x[i];
      const auto& y = pb.x[it->second];
      dx = std::max(dx, std::sqrt((x.x - y.x) * (x.x - y.x) + (x.y - y.y) * (x.y - y.y) + (x.z - y.z) * (x.z - y.z)));
    }
    fmt::print("{:>16}: {} and {} parcels, {} of A missing in B, largest |x_A - x_B| {:.3e} m (tol {:g} m)\n",
               "last_good.h5", pa.size(), pb.size(), missing, dx, pos_tol);
    ok = ok && missing == 0 && pa.size() == pb.size() && dx <= pos_tol;
    fmt::print("{}\n", ok ? "runs agree" : "RUNS DIFFER");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "compare_runs: {}\n", e.what());
    return 2;
  }
}
