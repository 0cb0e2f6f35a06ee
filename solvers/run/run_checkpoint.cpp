#include "solvers/run/run_checkpoint.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "core/revision.hpp"
#include "io/atomic_file.hpp"

namespace cgdem::run {

namespace {

constexpr uint64_t kMagic = 0x74706b636d656467ULL;          // "gdemckpt"
constexpr uint64_t kPortableMagic = 0x70706b636d656467ULL;  // "gdemckpp": format 1 of runs over ranks
// 3: one format for one process and N ranks (position, exact or portable DEM state);
// 2: one process only (RunCounters gained max_divergence_walls over 1).
constexpr uint32_t kVersion = 3;
enum Layout { kSingleProcess2 = 2, kCurrent = 3, kOverRanks1 = 101 };

// The stored entries of a field: every entry up to the last ghost of the last row.
size_t stored_size(const fluid::Field& f) {
  return static_cast<size_t>(f.index(f.ni() + fluid::kGhost - 1, f.nj() + fluid::kGhost - 1,
                                     f.nk() + fluid::kGhost - 1) + 1);
}

void put_field(io::ArchiveWriter& w, const fluid::Field& f) {
  w.put(f.extent());
  w.put_vector(std::vector<double>(f.data(), f.data() + stored_size(f)));
}

void get_field(io::ArchiveReader& r, fluid::Field& f, const std::string& name) {
  const auto e = r.get<std::array<int, 3>>();
  if (e != f.extent()) throw Error("checkpoint: air field " + name + " has another grid size than the case");
  std::vector<double> v;
  r.get_vector(v);
  if (v.size() != stored_size(f)) throw Error("checkpoint: air field " + name + " has the wrong size");
  std::copy(v.begin(), v.end(), f.data());
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read checkpoint " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

uint64_t fnv1a(const std::string& bytes) {
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char ch : bytes) h = (h ^ ch) * 1099511628211ULL;
  return h;
}

// The run's position field by field, laid out as the struct (and the portable format 1)
// holds it, with its 4 padding bytes written as zeros: the same state gives the same bytes.
void put_position(io::ArchiveWriter& w, const RunPosition& at) {
  w.put(at.t), w.put(at.steps), w.put(at.removed), w.put(at.builds);
  w.put(at.removed_damping), w.put(at.removed_friction), w.put(at.removed_walls), w.put(at.removed_fluid);
  w.put(at.ranks), w.put(int32_t{0});
  static_assert(sizeof(RunPosition) == 8 * 8 + 2 * sizeof(int32_t), "RunPosition's layout changed");
}

void get_position(io::ArchiveReader& r, RunPosition& at) {
  r.get(at.t), r.get(at.steps), r.get(at.removed), r.get(at.builds);
  r.get(at.removed_damping), r.get(at.removed_friction), r.get(at.removed_walls), r.get(at.removed_fluid);
  r.get(at.ranks), r.get<int32_t>();
}

// Where a DEM state loaded whole stands (an exact state, restarted over ranks).
RunPosition position_of(const DemSolver& dem) {
  RunPosition at;
  at.t = dem.time(), at.steps = dem.steps(), at.removed = dem.removed(), at.builds = dem.neighbor_builds();
  const EnergyBudget a = dem.removed_accounts();
  at.removed_damping = a.dissipated_damping, at.removed_friction = a.dissipated_friction;
  at.removed_walls = a.work_walls, at.removed_fluid = a.work_fluid;
  return at;
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

void write_checkpoint(const std::string& path, const std::string& config, ParticleStepper& s,
                      const SaveObservers& observers) {
  RunComm& comm = s.comm();
  const bool exact = comm.size() == 1;
  const RunPosition at = s.position();
  const parallel::PortableState parcels = exact ? parallel::PortableState{} : s.portable_state();
  const fluid::FluidState* air = s.with_air() ? &s.whole_air() : nullptr;
  comm.together("checkpoint", true, [&] {
    io::ArchiveWriter w;
    w.put(kMagic), w.put(kVersion);
    w.put_string(kGitRevision), w.put_string(config);
    w.put<uint8_t>(air != nullptr);
    w.tag("run");
    put_position(w, at);
    w.put<uint8_t>(exact);
    if (exact)
      s.dem().save(w);
    else
      parallel::save(w, parcels);
    if (air) put_air(w, *air);
    observers(w);
    w.tag("end");
    io::write_file_atomic(path, w.bytes());
  });
}

CheckpointReader::CheckpointReader(const std::string& path) : path_(path) {
  r_ = std::make_unique<io::ArchiveReader>(read_all(path), path);
  const auto magic = r_->get<uint64_t>();
  const auto version = r_->get<uint32_t>();
  if (magic == kPortableMagic && version == 1)
    layout_ = kOverRanks1;
  else if (magic == kMagic && (version == kVersion || version == 2))
    layout_ = static_cast<int>(version);
  else if (magic == kMagic || magic == kPortableMagic)
    throw Error(fmt::format("{}: checkpoint format {} of an earlier cgdem (this build reads formats 2 and {})", path,
                            version, kVersion));
  else
    throw Error(path + " is not a cgdem checkpoint");
  revision_ = r_->get_string();
  config_ = r_->get_string();
  with_air_ = r_->get<uint8_t>() != 0;
  if (layout_ != kSingleProcess2) {
    r_->tag("run");
    get_position(*r_, position_);
  }
  exact_ = layout_ == kCurrent ? r_->get<uint8_t>() != 0 : layout_ == kSingleProcess2;
}

CheckpointReader::CheckpointReader(CheckpointReader&&) noexcept = default;
CheckpointReader::~CheckpointReader() = default;

void CheckpointReader::restore(ParticleStepper& s, const LoadObservers& observers) {
  // A state settled in vacuum may go on with air (the air starts at rest around the parcels,
  // as in a fresh run); the other way round would drop the air's momentum and is refused.
  if (with_air_ && !s.with_air())
    throw Error(fmt::format("checkpoint {} was written by a run with air, the case runs without air", path_));
  if (exact_ && s.comm().size() == 1) {
    restore_exactly(s);
    observers(*r_);
  } else {
    restore_portably(s, observers);
  }
  r_->tag("end");
}

// One process from its own exact state: the solvers are made as for a fresh run, then
// their state is replaced, so that the run goes on bit for bit.
void CheckpointReader::restore_exactly(ParticleStepper& s) {
  const size_t in_case = s.dem().particles().size();
  s.place_parcels();
  if (with_air_) s.make_air();  // made before the load, as the run that wrote it made it
  s.dem().load(*r_);
  check_count(s.dem().particles().size(), s.dem().removed(), in_case);
  if (with_air_)
    get_air(*r_, s.air());
  else
    s.make_air();  // air at rest, its void fraction from the parcels just loaded (no-op in vacuum)
}

// Any other pairing: the parcels in id order, handed out to the ranks that own them.
void CheckpointReader::restore_portably(ParticleStepper& s, const LoadObservers& observers) {
  const size_t in_case = s.dem().particles().size();
  parallel::PortableState state;
  RunPosition at = position_;
  fluid::FluidState whole;
  if (with_air_) whole = fluid::make_fluid_state(s.air_spec().grid);
  s.comm().together("restart", false, [&] {
    if (exact_) {  // every rank loads the whole state, then takes its share of it
      s.dem().load(*r_);
      check_count(s.dem().particles().size(), s.dem().removed(), in_case);
      state = parallel::portable_state(s.dem().particles(), s.dem().neighbor_list());
      at = position_of(s.dem());
    } else {
      parallel::load(*r_, state);
      check_count(state.size(), at.removed, in_case);
    }
    if (layout_ == kOverRanks1) observers(*r_);  // that format held the air last
    if (with_air_) get_air(*r_, whole);
    if (layout_ != kOverRanks1) observers(*r_);
  });
  s.place_parcels(state, at);
  s.make_air();
  if (with_air_) s.take_air(whole);
}

void CheckpointReader::check_count(size_t present, long removed, size_t in_case) const {
  if (static_cast<long>(present) + removed != static_cast<long>(in_case))
    throw Error(fmt::format("checkpoint {} holds {} particles (+{} removed), the case inserts {}", path_, present,
                            removed, in_case));
}

uint64_t state_digest(const DemSolver& dem, const fluid::FluidState* air) {
  io::ArchiveWriter w;
  dem.save(w);
  if (air) put_air(w, *air);
  return fnv1a(w.bytes());
}

uint64_t state_digest(const parallel::PortableState& s) {
  io::ArchiveWriter w;
  parallel::save(w, s);
  return fnv1a(w.bytes());
}

}  // namespace cgdem::run
