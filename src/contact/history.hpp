// What every contact law shares with the rest of the engine:
//   * History: the record in which the neighbour lists keep a contact's state from one step
//     to the next, and which the checkpoints, the portable state and the migration buffers
//     write byte for byte. A law keeps its own history type and packs it into this record
//     (its history serialization, see laws.hpp), so none of those formats knows the law;
//   * OriginalPair: the l^3 original contacts a parcel contact stands for (docs/model.md,
//     section 1), from which a law derives its per-pair parameters;
//   * Work: the energy a contact dissipates in one step;
//   * select() and cgdem_sqrt(): what a law's force function may use and still vectorize.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/select.hpp"
#include "core/vec3.hpp"

// IEEE square root with vector variants (x86-64 vector function ABI, defined in
// simd_sqrt.cpp): a loop calling it vectorizes, while std::sqrt does not without
// -fno-math-errno. Same result as std::sqrt, lane by lane.
extern "C" {
#pragma omp declare simd notinbranch
double cgdem_sqrt(double);
}

namespace cgdem::contact {

// c ? a : b without a branch (core/select.hpp).
using cgdem::select;

// The stored history of one contact: eight doubles (one cache line, a group size the
// vectorizer handles), trivially copyable and without padding. The slots have a fixed
// frame rule, which is all that the lists, the migration and the portable state need to
// know: `xi` and `ft` are vectors in the frame of the pair's owner and are negated when the
// contact is seen from the partner's side (flipped()); `s1` and `s2` are scalars that do
// not depend on the side. All zero: a contact without history (empty()), which is what a
// law must leave when a contact ends. What the slots mean is the law's (its pack/unpack;
// linear_law.hpp: xi spring, ft last tangential force, s1 last v_n, s2 last F_t . v_t).
struct History {
  Vec3 xi;
  Vec3 ft;
  double s1 = 0;
  double s2 = 0;
  bool empty() const {
    return (xi.x == 0) & (xi.y == 0) & (xi.z == 0) & (ft.x == 0) & (ft.y == 0) & (ft.z == 0) & (s1 == 0) &
           (s2 == 0);
  }
  // The same contact seen from the partner's side.
  History flipped() const { return {-xi, -ft, s1, s2}; }
};

// The records of many contacts, kept as two arrays: the tangential springs `xi`, which every
// law's force reads and writes, and the other slots, which serve only the energy accounts
// (the force and the new xi depend on xi alone; laws.hpp). A force pass without the accounts
// (DemParams::accounts = false) touches only `xi`, 24 bytes a contact instead of 64, and
// the store then keeps no other slots (`accounts` false: `rest` stays empty and reads as
// zeros). A record is whole again where it leaves the lists (checkpoints, migration,
// the portable state).
struct HistoryStore {
  struct Rest {
    Vec3 ft;
    double s1 = 0;
    double s2 = 0;
  };
  std::vector<Vec3> xi;
  std::vector<Rest> rest;  // empty when !accounts
  bool accounts = true;

  size_t size() const { return xi.size(); }
  // Sizes both arrays (contents of new elements unspecified, as for a reused vector).
  void resize(size_t n) {
    xi.resize(n);
    rest.resize(accounts ? n : 0);
  }
  void clear() { xi.clear(), rest.clear(); }
  void swap(HistoryStore& o) {
    xi.swap(o.xi), rest.swap(o.rest);
    std::swap(accounts, o.accounts);
  }
  History get(size_t e) const {
    if (!accounts) return {xi[e], Vec3{}, 0, 0};
    const Rest& r = rest[e];
    return {xi[e], r.ft, r.s1, r.s2};
  }
  void set(size_t e, const History& h) {
    xi[e] = h.xi;
    if (accounts) rest[e] = {h.ft, h.s1, h.s2};
  }
  void push_back(const History& h) {
    xi.push_back(h.xi);
    if (accounts) rest.push_back({h.ft, h.s1, h.s2});
  }
  void pop_back() {
    xi.pop_back();
    if (accounts) rest.pop_back();
  }
  void assign(size_t n, const History& h) {
    resize(n);
    for (size_t e = 0; e < n; ++e) set(e, h);
  }
  bool empty(size_t e) const { return get(e).empty(); }
  // Every record, whole (for tests and tools; the engine reads the arrays).
  std::vector<History> records() const {
    std::vector<History> r(size());
    for (size_t e = 0; e < r.size(); ++e) r[e] = get(e);
    return r;
  }
};

// Energy bookkeeping of one contact over one step.
struct Work {
  double damping_n = 0;  // energy dissipated by the normal dashpot [J]
  double friction = 0;   // energy dissipated tangentially (dashpot and sliding) [J]
};

// The original contacts behind one parcel contact (paper eqs. 6-7): l3 simultaneous
// contacts between ORIGINAL particles, of reduced mass m_eff and reduced radius r_eff
// (particle-particle: m_O,i m_O,j / (m_O,i + m_O,j) and the same for the radii; against a
// wall: m_O and r_O, the wall a flat of infinite mass).
struct OriginalPair {
  double l3 = 1;
  double m_eff = 0;  // [kg]
  double r_eff = 0;  // [m]
  bool wall = false;
};

}  // namespace cgdem::contact
