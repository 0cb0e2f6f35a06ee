// What the contact-law registry (laws.hpp) gives the rest of the program: names, help,
// the [contact] reader, the tables of the chosen law.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "contact/laws.hpp"
#include "core/config.hpp"
#include "core/error.hpp"

namespace cgdem::contact {

namespace {

template <size_t... I>
std::string_view name_at(size_t i, std::index_sequence<I...>) {
  std::string_view name;
  ((i == I ? (name = std::get<I>(kContactLaws).name, true) : false) || ...);
  return name;
}
std::string_view name_at(size_t i) { return name_at(i, std::make_index_sequence<kContactLawCount>{}); }

template <size_t... I>
ContactModel read_law(size_t i, const Section& s, std::index_sequence<I...>) {
  ContactModel m;
  ((i == I ? (m = ContactModel(std::in_place_index<I>, std::get<I>(kContactLaws).read(s)), true) : false) || ...);
  return m;
}

}  // namespace

std::vector<std::string> contact_law_names() {
  std::vector<std::string> names;
  std::apply([&](const auto&... row) { (names.emplace_back(row.name), ...); }, kContactLaws);
  return names;
}

std::string contact_law_help() {
  std::string help;
  std::apply([&](const auto&... row) { ((help += fmt::format("  {:<14} {}\n", row.name, row.doc)), ...); },
             kContactLaws);
  return help;
}

std::string_view law_name(const ContactModel& model) { return name_at(model.index()); }
std::string_view law_name(const ContactTables& tables) { return name_at(tables.index()); }

ContactModel default_contact_model(std::string_view name) {
  ContactModel m;
  bool found = false;
  std::apply(
      [&]<class... Rows>(const Rows&... row) {
        ((row.name == name ? (m = typename Rows::Law::Material{}, found = true) : false) || ...);
      },
      kContactLaws);
  if (!found)
    throw Error(fmt::format("unknown contact law \"{}\" (the laws: {})", name, fmt::join(contact_law_names(), ", ")));
  return m;
}

ContactModel read_contact_model(const Section& s) {
  const std::vector<std::string> names = contact_law_names();
  const std::string law = s.string_or("law", names.front(), names);
  const size_t i = std::find(names.begin(), names.end(), law) - names.begin();
  return read_law(i, s, std::make_index_sequence<kContactLawCount>{});
}

ContactTables make_tables(const std::vector<Species>& species, const ContactModel& model) {
  return visit_law(model, [&](const auto& row, const auto& material) {
    using Law = typename std::decay_t<decltype(row)>::Law;
    return ContactTables(std::in_place_type<LawTable<Law>>, species, material);
  });
}

double min_collision_time(const std::vector<Species>& species, const ContactModel& model) {
  return visit_law(model, [&](const auto& row, const auto& material) {
    using Law = typename std::decay_t<decltype(row)>::Law;
    double t = INFINITY;
    for (const Species& a : species) {
      t = std::min(t, Law::collision_time(material, original_wall_pair(a)));
      for (const Species& b : species) t = std::min(t, Law::collision_time(material, original_pair(a, b)));
    }
    return t;
  });
}

}  // namespace cgdem::contact
