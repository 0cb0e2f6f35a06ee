// DemSolver::save / load: every piece of state a step reads, written verbatim, so that a
// restarted run repeats the uninterrupted one bit for bit. The neighbour lists are stored
// as they are (not rebuilt on loading): a rebuild would re-sort the particles and change
// the order of the force sums. Forces and torques of the last step are stored too (the
// first half kick after a restart uses them). The histories are the laws' records
// (contact/history.hpp); the section tag names the law when it is not the default one.
#include "solvers/dem/dem_solver.hpp"

#include <fmt/format.h>

namespace cgdem {

namespace {

// `io` takes each vector, `hist` the pair histories (written as whole records: the layout
// does not depend on whether the run keeps the energy accounts).
template <class Archive, class Hist, class P, class N>
void particle_and_list_fields(Archive&& io, Hist&& hist, P& p, N& nl) {
  for_each_field(p, io);  // every Particles field, in declaration order
  io(nl.offset), io(nl.partner), io(nl.image), hist(nl.hist), io(nl.rev_offset), io(nl.rev_entry);
  io(nl.wall_offset), io(nl.wall_part), io(nl.wall_hist), io(nl.x_at_build), io(nl.body_offset_at_build);
}

}  // namespace

std::string DemSolver::checkpoint_tag() const {
  return tables_.index() == 0 ? std::string("dem") : fmt::format("dem/{}", contact_law());
}

void DemSolver::save(io::ArchiveWriter& w) const {
  w.tag(checkpoint_tag());
  w.put(t_), w.put(steps_), w.put(removed_), w.put(forces_valid_);
  w.put(removed_damping_), w.put(removed_friction_), w.put(removed_walls_), w.put(removed_fluid_);
  w.put(nl_.builds), w.put(nl_.shift);
  particle_and_list_fields([&](const auto& v) { w.put_vector(v); },
                           [&](const contact::HistoryStore& h) {
                             w.put_generated<contact::History>(h.size(), [&h](size_t e) { return h.get(e); });
                           },
                           p_, nl_);
}

void DemSolver::load(io::ArchiveReader& r) {
  const std::string tag = r.get_string(), want = fmt::format("@{}", checkpoint_tag());
  if (tag != want) {
    if (tag == "@dem" || tag.starts_with("@dem/"))
      throw Error(fmt::format("checkpoint: written with contact law \"{}\", the case uses \"{}\"",
                              tag == "@dem" ? contact::contact_law_names().front() : tag.substr(5), contact_law()));
    throw Error("checkpoint: section 'dem' not found where expected");
  }
  r.get(t_), r.get(steps_), r.get(removed_), r.get(forces_valid_);
  r.get(removed_damping_), r.get(removed_friction_), r.get(removed_walls_), r.get(removed_fluid_);
  r.get(nl_.builds), r.get(nl_.shift);
  particle_and_list_fields([&](auto& v) { r.get_vector(v); },
                           [&](contact::HistoryStore& h) {
                             r.get_generated<contact::History>([&h](size_t n) { h.resize(n); },
                                                               [&h](size_t e, const contact::History& x) { h.set(e, x); });
                           },
                           p_, nl_);
  const size_t n = p_.x.size();
  // A solver that has not stepped yet (a run's checkpoint at its start) has no lists: its
  // first step builds them, as it did in the run that wrote the checkpoint.
  const bool unbuilt = !forces_valid_ && nl_.offset.empty();
  if (p_.id.size() != n || p_.v.size() != n || (!unbuilt && nl_.offset.size() != n + 1))
    throw Error("checkpoint: inconsistent particle or neighbour-list sizes");
  if (nl_.hist.size() != nl_.partner.size() || nl_.rev_entry.size() != nl_.partner.size())
    throw Error("checkpoint: inconsistent neighbour-list sizes");
  if (!unbuilt) nl_.derive();
  for (int s : p_.species)
    if (s < 0 || s >= static_cast<int>(species_.size())) throw Error("checkpoint: unknown species index");
  frame_ = scene_.at(t_);
}

}  // namespace cgdem
