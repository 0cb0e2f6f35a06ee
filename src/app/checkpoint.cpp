#include "app/checkpoint.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/revision.hpp"
#include "io/atomic_file.hpp"

namespace cgdem::app {

namespace {

constexpr uint64_t kMagic = 0x74706b636d656467ULL;  // "gdemckpt"
constexpr uint32_t kVersion = 2;  // 2: RunCounters gained max_divergence_walls

void put_field(io::ArchiveWriter& w, const fluid::Field& f) {
  w.put(f.extent());
  const size_t n = static_cast<size_t>(f.index(f.ni() + fluid::kGhost - 1, f.nj() + fluid::kGhost - 1,
                                               f.nk() + fluid::kGhost - 1) + 1);
  w.put_vector(std::vector<double>(f.data(), f.data() + n));
}

void get_field(io::ArchiveReader& r, fluid::Field& f, const std::string& name) {
  const auto e = r.get<std::array<int, 3>>();
  if (e != f.extent()) throw Error("checkpoint: air field " + name + " has another grid size than the case");
  std::vector<double> v;
  r.get_vector(v);
  const size_t n = static_cast<size_t>(f.index(f.ni() + fluid::kGhost - 1, f.nj() + fluid::kGhost - 1,
                                               f.nk() + fluid::kGhost - 1) + 1);
  if (v.size() != n) throw Error("checkpoint: air field " + name + " has the wrong size");
  std::copy(v.begin(), v.end(), f.data());
}


std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read checkpoint " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

void put_air(io::ArchiveWriter& w, const fluid::FluidState& a) {
  w.tag("air");
  w.put(a.t);
  for (const fluid::Field* f : {&a.u, &a.v, &a.w, &a.p, &a.eps, &a.eps_old}) put_field(w, *f);
}

void get_air(io::ArchiveReader& r, fluid::FluidState& air) {
  r.tag("air");
  r.get(air.t);
  const char* names[6] = {"u", "v", "w", "p", "eps", "eps_old"};
  fluid::Field* fs[6] = {&air.u, &air.v, &air.w, &air.p, &air.eps, &air.eps_old};
  for (int i = 0; i < 6; ++i) get_field(r, *fs[i], names[i]);
}

void write_checkpoint(const std::string& path, const std::string& config, const DemSolver& dem,
                      const fluid::FluidState* air, const DieDiagnostics& diag, const RunCounters& c) {
  io::ArchiveWriter w;
  w.put(kMagic), w.put(kVersion);
  w.put_string(kGitRevision), w.put_string(config);
  w.put<uint8_t>(air != nullptr);
  dem.save(w);
  if (air) put_air(w, *air);
  diag.save(w);
  w.tag("counters");
  w.put(c);
  w.tag("end");
  io::write_file_atomic(path, w.bytes());
}

std::string read_checkpoint(const std::string& path, DemSolver& dem, fluid::FluidState* air, DieDiagnostics& diag,
                            RunCounters& c) {
  io::ArchiveReader r(read_all(path), path);
  const uint64_t magic = r.get<uint64_t>();
  if (magic == kPortableCheckpointMagic)
    throw Error(path + " was written by a run over MPI ranks: restart it under mpirun (mpirun -np N cgdem run ... "
                       "--restart, any N >= 1)");
  if (magic != kMagic) throw Error(path + " is not a cgdem checkpoint");
  const uint32_t version = r.get<uint32_t>();
  if (version != kVersion && version != 1)
    throw Error(fmt::format("{}: checkpoint format version {} (this build reads 1 and {})", path, version, kVersion));
  const std::string revision = r.get_string();
  std::string config = r.get_string();
  if (revision != kGitRevision)
    fmt::print(stderr, "cgdem: warning: the checkpoint was written by revision {}, this is {}\n", revision,
               kGitRevision);
  const bool had_air = r.get<uint8_t>() != 0;
  if (had_air != (air != nullptr))
    throw Error(fmt::format("checkpoint {} was written by a run {} air, the case runs {} air", path,
                            had_air ? "with" : "without", air ? "with" : "without"));
  const size_t n_case = dem.particles().size();
  dem.load(r);
  if (dem.particles().size() + dem.removed() != n_case)
    throw Error(fmt::format("checkpoint {} holds {} particles (+{} removed), the case inserts {}", path,
                            dem.particles().size(), dem.removed(), n_case));
  if (air) get_air(r, *air);
  diag.load(r);
  r.tag("counters");
  if (version == 1) {  // before max_divergence_walls
    struct V1 {
      long fluid_steps, pressure_iterations, unconverged;
      double max_divergence;
    } old{};
    r.get(old);
    c = RunCounters{};
    c.fluid_steps = old.fluid_steps, c.pressure_iterations = old.pressure_iterations, c.unconverged = old.unconverged;
    c.max_divergence = old.max_divergence;  // then over every cell, walls included
  } else {
    r.get(c);
  }
  r.tag("end");
  return config;
}

bool is_portable_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  uint64_t magic = 0;
  return in.read(reinterpret_cast<char*>(&magic), sizeof magic) && magic == kPortableCheckpointMagic;
}

uint64_t state_digest(const DemSolver& dem, const fluid::FluidState* air) {
  io::ArchiveWriter w;
  dem.save(w);
  if (air) put_air(w, *air);
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char ch : w.bytes()) h = (h ^ ch) * 1099511628211ULL;
  return h;
}

}  // namespace cgdem::app
