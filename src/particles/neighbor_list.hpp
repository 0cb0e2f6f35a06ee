// Verlet neighbour lists built from a cell list, with contact history attached.
//
// Half lists: each pair is listed once, under its lower index i (the owner), with the
// partner j > i. The force pass evaluates each contact once, adds it to the owner and
// stores the partner's share per entry; a second pass gathers those shares for every
// particle through the reverse index (rev_offset/rev_entry), always in the same order.
// Every sum therefore has a fixed order: the result does not depend on the number of
// threads. A pair is listed when |x_i - x_j| < r_i + r_j + skin, a wall part when its
// surface lies within r_i + skin of x_i. The lists stay complete until some particle has
// moved more than skin/2 (plus the largest wall displacement, for wall candidates), or,
// given the spread of the particles' displacements (MoveBounds, one process), until two
// particles may have moved more than skin apart or a particle and a wall body more than
// skin (needs_rebuild below says why either suffices).
//
// Periodic axes: positions are wrapped into the period box at each build, and each entry
// carries the image of its partner (x_j + shift[image]). A periodic length must hold at
// least three cells of one interaction range, so that a pair has a single image.
//
// build() also sorts the particles along the cell grid (better cache use) and carries
// the tangential history of every pair and every particle-wall contact over to the new
// lists, by particle identity (negated when the pair's owner changes), together with the
// histories that parcels arriving from another rank brought along (`incoming`).
//
// Ghosts (MPI runs, solvers/dem_mpi/distributed_dem.hpp): the last `ghosts` particles are
// copies of other ranks' parcels near this rank's block. build() sorts only the others
// (the owned parcels) and leaves the ghosts where they are, lists no ghost-ghost pair and
// gives ghosts no wall candidates. Every ghost index is above every owned index, so a
// ghost is never an owner: an owned-ghost pair is listed under the owned parcel, with its
// history in the owned parcel's frame.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "contact/history.hpp"
#include "geometry/scene.hpp"
#include "particles/particles.hpp"

namespace cgdem {

// How far the particles moved since the last build: the largest |x_i - x_i(build)|^2 and,
// per axis, the least and the greatest x_i - x_i(build) (lo > hi: no particle). NaN is
// ignored, as in needs_rebuild.
struct MoveBounds {
  double max2 = 0;
  Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
};

struct Periodicity {
  std::array<bool, 3> axis{false, false, false};
  Vec3 lo, hi;  // the period box on the periodic axes
  bool any() const { return axis[0] || axis[1] || axis[2]; }
  // Moves x into [lo, hi) on the periodic axes.
  void wrap(Vec3& x) const;
};

// Contact history that travels with a parcel to another rank (src/parallel/migration.hpp),
// keyed by particle identity since local indices mean nothing there. A pair's history is
// in the frame of its particle of lower id (id_a < id_b); a wall contact's is in the
// particle's frame, as in the lists. Trivially copyable, without padding: these are also
// the records of the migration buffers.
struct CarriedPair {
  int64_t id_a, id_b;
  contact::History h;
};
struct CarriedWall {
  int64_t id;
  int64_t part;  // wall part index (the scene is the same on every rank)
  contact::History h;
};

struct NeighborList {
  double skin = 0;
  Periodicity periodic;
  // The last `ghosts` particles are ghost copies (see the header comment); 0 outside MPI
  // runs. Set by the caller before build(); retain() resets it to 0 (the particle set
  // changed). Not supported together with periodic axes (build() throws).
  size_t ghosts = 0;
  // Particle pairs (CSR over owners): entries offset[i] .. offset[i+1]-1.
  std::vector<int> offset, partner;
  std::vector<uint8_t> image;     // partner image: its position is x[partner] + shift[image]
  std::array<Vec3, 27> shift{};   // image shifts (index 13: none)
  // Contact history, in the owner's frame (xi and, with the energy accounts, the other
  // slots: contact/history.hpp). set_accounts() chooses whether the other slots are kept.
  contact::HistoryStore hist;
  // 1 when the pair was in contact at the last force pass (or, after a build or a load,
  // when its history is not empty); 0 implies an empty history. Derived (not saved).
  std::vector<uint8_t> live;
  // Reverse index: the entries whose partner is j are rev_entry[rev_offset[j] .. rev_offset[j+1]-1],
  // in increasing order; entry e sits at position rev_pos[e] (derived, not saved).
  std::vector<int> rev_offset, rev_entry, rev_pos;
  // Force pass output per reverse position rev_pos[e]: the force on the partner (= - on
  // the owner) and n x F_t (torque on the partner / -r_j); zero for pairs out of contact.
  std::vector<Vec3> f_partner, t_partner;
  // Per particle j: the lowest and highest owner among the entries whose partner is j
  // (-1: none). Derived.
  std::vector<int> first_owner, last_owner;
  // Force pass scratch (see compute_forces.cpp): per particle, 1 when all its entries are
  // evaluated by one thread (its partner shares are then summed directly into f_acc,
  // t_acc, zero between passes), for a team of direct_team threads (0: not set).
  std::vector<uint8_t> direct;
  std::vector<Vec3> f_acc, t_acc;
  int direct_team = 0;
  // Particle-wall candidates (CSR over wall parts).
  std::vector<int> wall_offset, wall_part;
  std::vector<contact::History> wall_hist;
  // Build scratch: the storage of the lists before last, which the next build() fills
  // again instead of allocating. At 540,000 particles the pair histories alone take
  // 240 MB; a fresh array of that size comes from the system at every build, and its
  // pages are faulted in and zeroed one by one. Contents meaningless; not saved.
  // The same for the pair search's per-thread results and the sort of the particles.
  struct Spare {
    std::vector<int> offset, partner, wall_offset, wall_part;
    contact::HistoryStore hist;
    std::vector<contact::History> wall_hist;
    std::vector<std::vector<std::pair<int, int>>> found;  // per thread: (partner, image code)
    Particles::ReorderScratch sort;
  } spare;
  // State at the last build, for the rebuild criterion.
  std::vector<Vec3> x_at_build;
  std::vector<Vec3> body_offset_at_build;
  long builds = 0;
  // Histories carried in by parcels that arrived since the last build: the next build()
  // attaches each one to its pair or wall contact by particle id (flipping a pair's
  // history when its owner, the lower local index, is the particle id_b), then clears
  // them. One whose contact is not in the new lists is dropped, as build() drops the
  // history of contacts that came apart. Transient: not saved in checkpoints.
  struct Incoming {
    std::vector<CarriedPair> pairs;
    std::vector<CarriedWall> walls;
    bool empty() const { return pairs.empty() && walls.empty(); }
  } incoming;

  // Whether the pair histories keep the slots of the energy accounts (true by default):
  // set before the first build or load; clears the lists' histories when it changes.
  void set_accounts(bool on);
  // Wraps and sorts `p` (dropping nothing), rebuilds the lists and carries history over
  // (neighbor_build.cpp, in named steps). The result does not depend on the thread count.
  void build(Particles& p, const geometry::Scene::Frame& walls);
  // Follows a change of the particle set made between builds (parcels sent to or received
  // from another rank): particle k < keep.size() is the old particle keep[k] (keep
  // increasing, as for Particles::reorder), the n_added after them are new. Keeps the
  // history of the pairs and wall contacts among the kept particles, renumbered, so that
  // the next build() carries it over; clears the derived fields, and needs_rebuild() is
  // true until that build. Without lists (never built) it does nothing but reset `ghosts`.
  void retain(const std::vector<int>& keep, size_t n_added);
  // Recomputes live, rev_pos, first_owner, last_owner and clears f_acc, t_acc (after
  // build() or after the saved fields were loaded); throws when the lists or the reverse
  // index are out of range. f_partner and t_partner are sized, not cleared: the force pass
  // clears them before it first reads them (direct_team is reset).
  void derive();
  // How far the particles moved since the last build (the first min(p.size(), built) of
  // them; DemSolver computes the same while it drifts them).
  MoveBounds moved_since_build(const Particles& p) const;
  // True when the lists may have become incomplete (each particle's own displacement).
  bool needs_rebuild(const Particles& p, const geometry::Scene::Frame& walls) const;
  // The same test, given how far the particles moved (computed by the caller while it moved
  // them). With `relative`, also the test of the relative displacements, and a build only
  // when both ask for one (either proves the lists complete; the relative one keeps them
  // longer when the particles move together or with a wall body, the per-particle one when
  // they wander each its own way):
  //   pairs: with D the centre of the displacements' bounding box, every |dx_i - D| <= h,
  //          h = |(hi - lo)/2|, so |dx_i - dx_j| <= 2h: no pair unlisted at the build
  //          (gap >= skin) can touch while 2h < skin;
  //   walls: a part's signed distance is 1-Lipschitz (exact primitives; min and max of
  //          them) and bodies translate, so a part that was no candidate (distance >=
  //          r + skin) cannot touch while |dx_i - dw_b| < skin for its body b; over the
  //          bounding box that is max(hi - dw_b, dw_b - lo) per axis.
  // Not for runs over several blocks: a rank's ghost layer and migration need each
  // particle's own displacement below skin/2 (the test without `relative`).
  bool needs_rebuild(const MoveBounds& moved, size_t n, const geometry::Scene::Frame& walls, bool relative) const;
  size_t pair_entries() const { return partner.size(); }
  bool valid_for(const Particles& p) const { return offset.size() == p.size() + 1; }
  // Particles that are not ghosts: indices 0 .. owned(p) - 1.
  size_t owned(const Particles& p) const { return p.size() - ghosts; }
  // The partner's position as seen from the owner (periodic image applied).
  Vec3 partner_x(const Particles& p, int e) const { return p.x[partner[e]] + shift[image[e]]; }
};

}  // namespace cgdem
