#include "parallel/portable_state.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "core/error.hpp"

namespace cgdem::parallel {

namespace {

bool pair_less(const CarriedPair& a, const CarriedPair& b) {
  return a.id_a != b.id_a ? a.id_a < b.id_a : a.id_b < b.id_b;
}
bool wall_less(const CarriedWall& a, const CarriedWall& b) { return a.id != b.id ? a.id < b.id : a.part < b.part; }

// Sorts s.p by id (and the records by their keys) and checks that no id or record repeats.
void normalise(PortableState& s) {
  std::vector<int> order(s.p.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return s.p.id[a] < s.p.id[b]; });
  s.p.reorder(order);
  for (size_t k = 1; k < s.p.size(); ++k)
    if (s.p.id[k] == s.p.id[k - 1]) throw Error(fmt::format("portable state: parcel id {} is held twice", s.p.id[k]));
  std::sort(s.pairs.begin(), s.pairs.end(), pair_less);
  for (size_t k = 1; k < s.pairs.size(); ++k)
    if (!pair_less(s.pairs[k - 1], s.pairs[k]))
      throw Error(fmt::format("portable state: the history of pair ({}, {}) is recorded twice", s.pairs[k].id_a,
                              s.pairs[k].id_b));
  std::sort(s.walls.begin(), s.walls.end(), wall_less);
  for (size_t k = 1; k < s.walls.size(); ++k)
    if (!wall_less(s.walls[k - 1], s.walls[k]))
      throw Error(fmt::format("portable state: the history of parcel {} on wall part {} is recorded twice",
                              s.walls[k].id, s.walls[k].part));
}

template <class T>
void append_all(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

}  // namespace

PortableState portable_state(const Particles& p, const NeighborList& nl, size_t n_owned) {
  if (n_owned > p.size())
    throw Error(fmt::format("portable state: {} owned parcels of {}", n_owned, p.size()));
  const bool lists = !nl.offset.empty();
  if (lists && !nl.valid_for(p))
    throw Error(fmt::format("portable state: the neighbour lists hold {} particles, the particles {}",
                            nl.offset.size() - 1, p.size()));
  PortableState s;
  std::vector<int> owned(n_owned);
  std::iota(owned.begin(), owned.end(), 0);
  s.p = p;
  s.p.reorder(owned);
  const int no = static_cast<int>(n_owned);
  if (lists) {
    for (int i = 0; i < static_cast<int>(p.size()); ++i) {
      for (int e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
        const int j = nl.partner[e];
        if (nl.hist.empty(e)) continue;
        const bool oi = i < no, oj = j < no;
        if (!oi && !oj) continue;  // two ghosts: another rank's pair
        const bool i_lower = p.id[i] < p.id[j];
        if (oi != oj && !(i_lower ? oi : oj)) continue;  // split pair: recorded by the lower id's rank
        s.pairs.push_back(i_lower ? CarriedPair{p.id[i], p.id[j], nl.hist.get(e)}
                                  : CarriedPair{p.id[j], p.id[i], nl.hist.get(e).flipped()});
      }
      if (i >= no) continue;
      for (int e = nl.wall_offset[i]; e < nl.wall_offset[i + 1]; ++e)
        if (!nl.wall_hist[e].empty()) s.walls.push_back({p.id[i], nl.wall_part[e], nl.wall_hist[e]});
    }
  }
  // Records queued by a migration since the last build belong to parcels that are here now.
  if (!nl.incoming.empty()) {
    std::vector<int64_t> ids(s.p.id);
    std::sort(ids.begin(), ids.end());
    auto here = [&](int64_t id) { return std::binary_search(ids.begin(), ids.end(), id); };
    for (const CarriedPair& c : nl.incoming.pairs)
      if (here(c.id_a) && !c.h.empty()) s.pairs.push_back(c);
    for (const CarriedWall& c : nl.incoming.walls)
      if (here(c.id) && !c.h.empty()) s.walls.push_back(c);
  }
  normalise(s);
  return s;
}

PortableState merge(std::vector<PortableState> parts) {
  PortableState all;
  for (PortableState& q : parts) {
    all.p.append(q.p);
    append_all(all.pairs, q.pairs);
    append_all(all.walls, q.walls);
    q = PortableState{};
  }
  normalise(all);
  return all;
}

size_t restore(const PortableState& s, const std::function<bool(const Vec3&)>& mine, Particles& p,
               NeighborList& nl) {
  std::vector<int> taken;
  for (size_t i = 0; i < s.p.size(); ++i)
    if (mine(s.p.x[i])) taken.push_back(static_cast<int>(i));
  Particles add = s.p;
  add.reorder(taken);
  p.append(add);
  std::vector<int64_t> ids(add.id);  // increasing: s.p is
  auto here = [&](int64_t id) { return std::binary_search(ids.begin(), ids.end(), id); };
  for (const CarriedPair& c : s.pairs)
    if (here(c.id_a) || here(c.id_b)) nl.incoming.pairs.push_back(c);
  for (const CarriedWall& c : s.walls)
    if (here(c.id)) nl.incoming.walls.push_back(c);
  return taken.size();
}

void save(io::ArchiveWriter& w, const PortableState& s) {
  w.tag("portable-dem");
  for_each_field(s.p, [&](const auto& field) { w.put_vector(field); });
  w.put_vector(s.pairs);
  w.put_vector(s.walls);
}

void load(io::ArchiveReader& r, PortableState& s) {
  r.tag("portable-dem");
  s = PortableState{};
  for_each_field(s.p, [&](auto& field) { r.get_vector(field); });
  r.get_vector(s.pairs);
  r.get_vector(s.walls);
  const size_t n = s.p.id.size();
  bool sizes = true;
  for_each_field(s.p, [&](const auto& field) { sizes = sizes && field.size() == n; });
  if (!sizes) throw Error("portable state: the particle fields have different lengths");
  for (size_t k = 1; k < n; ++k)
    if (!(s.p.id[k - 1] < s.p.id[k])) throw Error("portable state: parcels are not in increasing id");
}

}  // namespace cgdem::parallel
