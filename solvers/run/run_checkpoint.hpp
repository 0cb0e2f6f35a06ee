// Checkpoints of a run (`<output>/checkpoint.bin`, `settled.bin`): one format, written by
// one process or by N MPI ranks, and restarted on any number of ranks, one process
// included. The file holds, in this order:
//
//   magic "gdemckpt", format version, the cgdem revision, the resolved configuration, with
//   or without air, the run's position (RunPosition), the DEM state, the air of the whole
//   grid (with air), the observers' state (the run's diagnostics and counters, written by
//   the caller), "end".
//
// The DEM state comes in one of two forms:
//   * exact (written by one process): DemSolver::save, the particles in their order with
//     the neighbour lists and contact histories as they are, and the air with its ghost
//     layers: a run restarted from it on one process continues bit for bit as if it had
//     never stopped;
//   * portable (written over ranks): parcels in increasing id with id-keyed histories
//     (parallel/portable_state.hpp), the air's interior entries.
// Restarted on N ranks an exact state is first loaded whole on every rank and handed out
// as a portable one; restarted on one process a portable state is handed out to it alone.
// Either way only the order of the force sums differs from the run that wrote it.
//
// Checkpoints of earlier cgdem versions (single-process format 2, the portable format 1 of
// runs over ranks) are read too. The moving walls need no state: their position is a
// function of time.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "io/archive.hpp"
#include "solvers/run/particle_stepper.hpp"

namespace cgdem::run {

// The observers' part of a checkpoint (the caller's diagnostics and counters).
using SaveObservers = std::function<void(io::ArchiveWriter&)>;
using LoadObservers = std::function<void(io::ArchiveReader&)>;

// Collective: writes the state of the run to `path` on rank 0 (atomically), exact on one
// process, portable over ranks. Errors are raised on every rank together.
void write_checkpoint(const std::string& path, const std::string& config, ParticleStepper& s,
                      const SaveObservers& observers);

class CheckpointReader {
 public:
  // Reads the file and its header. Throws cgdem::Error for a file that is not a cgdem
  // checkpoint or of an unknown format version.
  explicit CheckpointReader(const std::string& path);
  CheckpointReader(CheckpointReader&&) noexcept;
  ~CheckpointReader();

  const std::string& path() const { return path_; }
  const std::string& config() const { return config_; }
  const std::string& revision() const { return revision_; }
  int ranks() const { return position_.ranks; }  // that wrote it
  bool exact() const { return exact_; }
  bool with_air() const { return with_air_; }

  // Collective: the whole set-up of `s` (ParticleStepper steps 1-3) in the checkpoint's
  // state, then the observers'. Throws cgdem::Error when the checkpoint does not belong to
  // the case (parcel count, air grid, air in the checkpoint but not in the case). A
  // checkpoint without air restarts a case with air: the air starts at rest at its time.
  void restore(ParticleStepper& s, const LoadObservers& observers);

 private:
  void restore_exactly(ParticleStepper& s);
  void restore_portably(ParticleStepper& s, const LoadObservers& observers);
  void check_count(size_t present, long removed, size_t in_case) const;

  std::string path_, bytes_, revision_, config_;
  int layout_ = 0;  // the format version (the portable format 1 as its own layout)
  bool exact_ = true, with_air_ = false;
  RunPosition position_;
  std::unique_ptr<io::ArchiveReader> r_;  // positioned after the header
};

// The air state as a checkpoint holds it: t and the fields u, v, w, p, eps, eps_old with
// their ghost layers. get_air throws cgdem::Error for fields of another grid size.
void put_air(io::ArchiveWriter& w, const fluid::FluidState& air);
void get_air(io::ArchiveReader& r, fluid::FluidState& air);

// 64-bit FNV-1a digest of the physical state, printed at the end of a run so that two runs
// can be compared bit for bit: of the DEM archive and the air fields (one process), or of
// the portable state of every parcel (over ranks; `s` on rank 0).
uint64_t state_digest(const DemSolver& dem, const fluid::FluidState* air);
uint64_t state_digest(const parallel::PortableState& s);

}  // namespace cgdem::run
