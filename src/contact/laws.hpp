// The contact-law registry: every law a case may choose with [contact] law = "NAME".
//
// A law is a policy class (linear_law.hpp, hertz_mindlin.hpp are the examples) with
//   Material   what a case gives ([contact] keys), read by `read`
//   Params     what the force function reads for one species pair or species-wall kind
//              (small and trivially copyable: the force pass keeps one in registers)
//   History    what one contact carries from step to step, with
//              pack(History) -> contact::History and unpack(contact::History) -> History:
//              its serialization into the eight-double record the lists, checkpoints and
//              migration buffers keep (history.hpp: xi and ft negate when the contact is
//              seen from the partner, s1 and s2 do not; all zero = no contact)
//   static Params params(const Material&, const OriginalPair&)
//   static double collision_time(const Material&, const OriginalPair&)  (time-step check)
//   static Vec3 force(const Params&, n, delta, v_rel, History&, dt, Vec3& f_t, Work&)
//              a pure function of its inputs, branch-free (the force pass vectorizes it),
//              giving exactly the negated force from the partner's side; the force and
//              the new xi slot depend on the record's xi slot alone (the other slots feed
//              only Work), so that a run without the energy accounts keeps only xi
//              (history.hpp, HistoryStore) and moves exactly as one with them
//   static void finish(const Params&, n, v_rel, History&, dt, Work&)  (contact ended)
//   static double elastic_energy(const Params&, double delta, const History&)  (reads xi only)
//   static Material read(const Section&)
// and one row in kContactLaws below: its name, one line of documentation and its reader.
// The force pass (solvers/dem/compute_forces.cpp), the energy budget, the tables, the
// checkpoints and the config reader are instantiated for every row; nothing else changes
// when a law is added (docs/contact_laws.md).
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "contact/hertz_mindlin.hpp"
#include "contact/law_table.hpp"
#include "contact/linear_law.hpp"

namespace cgdem::contact {

template <class L>
struct LawRow {
  using Law = L;
  std::string_view name;  // the value of [contact] law
  std::string_view doc;   // one line, for --help and docs
  typename L::Material (*read)(const Section&);
};

// The registry. The first row is the default law.
inline constexpr std::tuple kContactLaws{
    LawRow<LinearSpringDashpot>{"linear",
                                "linear spring-dashpot, Coulomb friction, tangential history, l^3 scaling (the "
                                "paper's eqs. 6-7); keys stiffness, restitution, friction",
                                &LinearSpringDashpot::read},
    LawRow<HertzMindlin>{"hertz-mindlin",
                         "Hertz normal, Mindlin no-slip tangential stiffness, restitution-calibrated dashpots, "
                         "l^3 scaling; keys youngs_modulus, poisson_ratio, restitution, friction",
                         &HertzMindlin::read},
};

namespace detail {
template <class Rows>
struct PerRow;
template <class... Rows>
struct PerRow<std::tuple<Rows...>> {
  using Materials = std::variant<typename Rows::Law::Material...>;
  using Tables = std::variant<LawTable<typename Rows::Law>...>;
};
using Rows = std::remove_cv_t<decltype(kContactLaws)>;
}  // namespace detail

// The law of a case with its material: alternative i is row i's Material.
using ContactModel = detail::PerRow<detail::Rows>::Materials;
// The parameter tables of the chosen law: alternative i is row i's LawTable.
using ContactTables = detail::PerRow<detail::Rows>::Tables;

inline constexpr size_t kContactLawCount = std::tuple_size_v<detail::Rows>;

// f(row, material) with the row of the model's law (f's result type must not depend on the row).
template <class F>
decltype(auto) visit_law(const ContactModel& model, F&& f) {
  return [&]<size_t... I>(std::index_sequence<I...>) -> decltype(auto) {
    using R = decltype(f(std::get<0>(kContactLaws), std::get<0>(model)));
    if constexpr (std::is_void_v<R>) {
      ((model.index() == I ? (f(std::get<I>(kContactLaws), std::get<I>(model)), true) : false) || ...);
    } else {
      R r{};
      ((model.index() == I ? (r = f(std::get<I>(kContactLaws), std::get<I>(model)), true) : false) || ...);
      return r;
    }
  }(std::make_index_sequence<kContactLawCount>{});
}

// The tables of the model's law.
ContactTables make_tables(const std::vector<Species>& species, const ContactModel& model);
// Name of the model's law (its row's name).
std::string_view law_name(const ContactModel& model);
std::string_view law_name(const ContactTables& tables);
// Names of every law, in registry order (the config's "allowed:" list).
std::vector<std::string> contact_law_names();
// "NAME  doc" per law, one a line (for --help).
std::string contact_law_help();
// The default material (Material{}) of the law named `name`; throws Error naming the laws.
ContactModel default_contact_model(std::string_view name);
// Reads [contact]: law (default: the first row) and that law's keys.
ContactModel read_contact_model(const Section& contact);
// Shortest collision time over every species pair and wall (the time-step check).
double min_collision_time(const std::vector<Species>& species, const ContactModel& model);

}  // namespace cgdem::contact
