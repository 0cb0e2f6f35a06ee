// How a solver on the air grid, or on one block of it, fills the ghost layers of its fields
// and reduces grid-wide values (issue 6: the air inside `mpirun -np N cgdem run`).
//
// The air's solvers never fill ghosts or take a maximum over the grid themselves; they ask
// a FieldSync:
//   SerialSync              the whole grid in one process: the fills of boundary.hpp with
//                           the case's boundary conditions; reductions are the values
//                           themselves. The serial solvers make exactly the calls they made
//                           before this interface existed (results unchanged, bit for bit).
//   air_mpi::HaloSync       one block per MPI rank: the same fills on the block's physical
//                           sides, the halo exchange on its cut sides, reductions over the
//                           ranks (src/parallel/mpi/halo_sync.hpp).
// A solver on a block is given the block's grid and the block's boundary conditions, with
// every cut side marked Open (air_mpi::local_boundary): its face ranges then include the
// faces next to a cut, and is_cut() tells it which Open sides are not really open (no
// boundary pressure enters the pressure equation there).
// Every call is collective when the FieldSync spans several ranks: all ranks make the same
// calls in the same order.
#pragma once
#include <string>

#include "fluid/boundary.hpp"

namespace cgdem::fluid {

// Cell-centred fields have no stagger axis (face fields of component d: stagger d).
inline constexpr int kCells = -1;

class FieldSync {
 public:
  virtual ~FieldSync() = default;
  // Ghost layers (and prescribed boundary faces) as boundary.hpp defines them.
  virtual void fill_scalar(Field& s, ScalarKind kind) = 0;
  virtual void fill_velocity(Field& u, Field& v, Field& w) = 0;
  virtual void fill_velocity_component(int d, Field& f) = 0;
  // A field without boundary fill (wall fractions): the cut-side ghost layers get the values
  // of the blocks that own them; physical-side ghosts are left as they are.
  virtual void copy_ghosts(Field& f, int stagger) = 0;
  // A deposit that reached into cut-side ghost layers: those entries are added to the blocks
  // that own them (in a fixed order) and the ghosts then copied back, so that every block
  // holds the summed values on its entries and ghosts.
  virtual void sum_deposits(Field& f, int stagger) = 0;
  // Side s = 2 axis + (0 low, 1 high) borders another block.
  virtual bool is_cut(int side) const = 0;
  // In place: the maximum of each of v[0 .. n-1] over the ranks.
  virtual void max(double* v, int n) = 0;
  virtual double sum(double v) = 0;
  virtual long sum(long v) = 0;
  virtual bool any(bool v) = 0;
  // Throws cgdem::Error on every rank when `failed` holds on any: this rank's message where
  // it failed, a pointer to the failing rank elsewhere (serial: throws `message` if failed).
  virtual void raise_if(bool failed, const std::string& message) = 0;
};

class SerialSync final : public FieldSync {
 public:
  SerialSync(const MacGrid& g, const FluidBoundary& bc) : g_(g), bc_(bc) {}
  void fill_scalar(Field& s, ScalarKind kind) override { fill_scalar_ghosts(g_, bc_, s, kind); }
  void fill_velocity(Field& u, Field& v, Field& w) override { fill_velocity_ghosts(g_, bc_, u, v, w); }
  void fill_velocity_component(int d, Field& f) override { fill_velocity_component_ghosts(g_, bc_, d, f); }
  void copy_ghosts(Field&, int) override {}
  void sum_deposits(Field&, int) override {}
  bool is_cut(int) const override { return false; }
  void max(double*, int) override {}
  double sum(double v) override { return v; }
  long sum(long v) override { return v; }
  bool any(bool v) override { return v; }
  void raise_if(bool failed, const std::string& message) override {
    if (failed) throw Error(message);
  }

 private:
  MacGrid g_;
  FluidBoundary bc_;
};

}  // namespace cgdem::fluid
