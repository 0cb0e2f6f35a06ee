// The contact-law registry (contact/laws.hpp): the names the config reader and the help
// take, the [contact] reader, and what every registered law must satisfy to live in the
// force pass, the lists and the checkpoints. The per-law checks run over every row, so a
// law added to the registry is checked without editing this file.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstring>
#include <random>

#include "contact/laws.hpp"
#include "core/config.hpp"
#include "dem_test_util.hpp"
#include "io/archive.hpp"

namespace cgdem {
namespace {

TEST(ContactRegistry, NamesHelpAndDefault) {
  const std::vector<std::string> names = contact::contact_law_names();
  ASSERT_EQ(names.size(), contact::kContactLawCount);
  EXPECT_EQ(names.front(), "linear");  // the paper's law is the default
  const std::string help = contact::contact_law_help();
  for (const auto& n : names) EXPECT_NE(help.find(n), std::string::npos) << n;
  std::printf("[ registry ] %zu laws:\n%s", names.size(), help.c_str());
}

contact::ContactModel read(const std::string& toml) {
  Config cfg = Config::from_string(toml);
  contact::ContactModel m = contact::read_contact_model(cfg.root().section("contact"));
  cfg.check_unused();
  return m;
}

TEST(ContactRegistry, ReaderTakesTheLawAndItsKeys) {
  const contact::ContactModel lin = read("[contact]\nstiffness = 40.0\nrestitution = 0.8\nfriction = 0.2\n");
  ASSERT_EQ(lin.index(), 0u);
  EXPECT_EQ(std::get<MaterialParams>(lin).stiffness, 40.0);
  EXPECT_EQ(std::get<MaterialParams>(lin).wall_friction, 0.2);
  const contact::ContactModel hm = read(
      "[contact]\nlaw = \"hertz-mindlin\"\nyoungs_modulus = 1e7\npoisson_ratio = 0.25\nrestitution = 0.8\n"
      "friction = 0.2\nwall_youngs_modulus = 2e8\n");
  EXPECT_EQ(contact::law_name(hm), "hertz-mindlin");
  const auto& h = std::get<HertzMindlinMaterial>(hm);
  EXPECT_EQ(h.youngs_modulus, 1e7);
  EXPECT_EQ(h.wall_youngs_modulus, 2e8);
  EXPECT_EQ(h.wall_poisson_ratio, 0.25);
  EXPECT_EQ(h.max_impact_speed, 1.0);
}

TEST(ContactRegistry, ReaderMessagesNameTheRegistry) {
  auto message = [](const std::string& toml) {
    try {
      read(toml);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string unknown = message("[contact]\nlaw = \"hooke\"\nstiffness = 1.0\n");
  const std::string other_keys = message("[contact]\nlaw = \"hertz-mindlin\"\nstiffness = 50.0\n");
  const std::string unused = message(
      "[contact]\nstiffness = 50.0\nrestitution = 0.9\nfriction = 0.3\npoisson_ratio = 0.3\n");
  std::printf("[ registry ] %s\n[ registry ] %s\n[ registry ] %s\n", unknown.c_str(), other_keys.c_str(),
              unused.c_str());
  const std::vector<std::string> names = contact::contact_law_names();
  EXPECT_NE(unknown.find(fmt::format("expected one of {}, got \"hooke\"", fmt::join(names, ", "))), std::string::npos);
  EXPECT_NE(other_keys.find("contact.youngs_modulus"), std::string::npos);
  EXPECT_NE(unused.find("contact.poisson_ratio"), std::string::npos);
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  const Vec3 v{g(rng), g(rng), g(rng)};
  return v / norm(v);
}

// Every law: Newton's third law to the bit (the partner's side: n, v_rel and the record's
// vectors negated), history that survives pack/unpack bit for bit, finish() leaving an
// empty record; sticking and sliding contacts, random geometry.
template <class Row>
void check_law(const Row& row) {
  using Law = typename Row::Law;
  const Species s = test::powder(3);
  const typename Law::Params p = Law::params(typename Law::Material{}, contact::original_pair(s, s));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int differ = 0, sliding = 0, cases = 0;
  for (int c = 0; c < 2000; ++c) {
    const Vec3 n = random_unit(rng);
    const double delta = 1e-7 * u(rng), dt = 1e-6;
    const Vec3 v_rel = std::pow(10.0, -7 + 6.7 * u(rng)) * random_unit(rng);  // 1e-7 .. 0.5 m/s
    typename Law::History a{}, b{};
    Vec3 fta, ftb, fa;
    contact::Work wa, wb;
    for (int step = 0; step < 3; ++step) {  // a few steps, so that the history is not empty
      fa = Law::force(p, n, delta, v_rel, a, dt, fta, wa);
      const Vec3 fb = Law::force(p, -n, delta, -v_rel, b, dt, ftb, wb);
      const contact::History ra = Law::pack(a), rb = Law::pack(b), flip = rb.flipped();
      differ += !(fa.x == -fb.x && fa.y == -fb.y && fa.z == -fb.z && fta.x == -ftb.x && fta.y == -ftb.y &&
                  fta.z == -ftb.z && wa.damping_n == wb.damping_n && wa.friction == wb.friction);
      differ += !(ra.xi.x == flip.xi.x && ra.xi.y == flip.xi.y && ra.xi.z == flip.xi.z && ra.ft.x == flip.ft.x &&
                  ra.ft.y == flip.ft.y && ra.ft.z == flip.ft.z && ra.s1 == flip.s1 && ra.s2 == flip.s2);
      const contact::History again = Law::pack(Law::unpack(ra));
      differ += std::memcmp(&again, &ra, sizeof ra) != 0;
      ++cases;
    }
    if constexpr (requires { p.mu; })  // on the Coulomb cone at the last step
      sliding += norm(fta) >= (1 - 1e-12) * p.mu * norm(fa - fta);
    Law::finish(p, n, v_rel, a, dt, wa);
    differ += !Law::pack(a).empty();
  }
  std::printf("[ registry ] law %.*s: %d evaluations (%d contacts sliding at the end), %d differ from the partner's "
              "side or the round trip\n",
              static_cast<int>(row.name.size()), row.name.data(), cases, sliding, differ);
  EXPECT_GT(sliding, 200);  // both branches, each in at least a tenth of the contacts
  EXPECT_LT(sliding, 1800);
  EXPECT_EQ(differ, 0) << row.name;
}

TEST(ContactRegistry, EveryLawIsAntisymmetricAndSerializes) {
  std::apply([](const auto&... row) { (check_law(row), ...); }, contact::kContactLaws);
}

// Every law runs in the solver and restarts bit-identically from a checkpoint; a checkpoint
// is refused by a solver of another law, with both names. The solver: 20 spinning parcels
// (l = 2) falling onto a floor, the law's default material.
template <class Law>
DemSolver floor_solver() {
  DemParams prm;
  prm.dt = 1e-6;
  prm.domain = {{-1, -1, -1}, {1, 1, 1}};
  DemSolver dem({test::powder(2)}, typename Law::Material{}, prm, test::floor_scene());
  for (int k = 0; k < 20; ++k)
    dem.particles().add(k, 0, dem.species()[0], {1e-4 * (k % 4), 3e-4 * (k / 4 % 2), 2.4e-4 + 2.6e-4 * (k / 8)},
                        {0.01 * (k % 3), 0, -0.05}, {0, 30.0 * k, 0});
  return dem;
}

template <class Row>
std::string checkpoint_of(const Row&, int steps) {
  DemSolver dem = floor_solver<typename Row::Law>();
  for (int k = 0; k < steps; ++k) dem.step();
  io::ArchiveWriter w;
  dem.save(w);
  return w.bytes();
}

TEST(ContactRegistry, EveryLawCheckpointsAndRefusesAnother) {
  int tested = 0;
  std::apply(
      [&](const auto&... row) {
        (
            [&](const auto& r) {
              using Law = typename std::decay_t<decltype(r)>::Law;
              const std::string whole = checkpoint_of(r, 600);  // 600 steps straight
              // 300 steps, save, load into a fresh solver, 300 more
              DemSolver again = floor_solver<Law>();
              io::ArchiveReader rd(checkpoint_of(r, 300), "half");
              again.load(rd);
              for (int k = 0; k < 300; ++k) again.step();
              io::ArchiveWriter w;
              again.save(w);
              EXPECT_TRUE(w.bytes() == whole) << r.name;
              std::printf("[ registry ] law %.*s: 300 + 300 steps through a checkpoint %s 600 steps\n",
                          static_cast<int>(r.name.size()), r.name.data(),
                          w.bytes() == whole ? "equal to" : "DIFFER from");
              ++tested;
            }(row),
            ...);
      },
      contact::kContactLaws);
  EXPECT_EQ(tested, static_cast<int>(contact::kContactLawCount));
  // Every other law's checkpoint in a solver of the default law: refused, both named.
  using DefaultLaw = typename std::decay_t<decltype(std::get<0>(contact::kContactLaws))>::Law;
  DemSolver first({test::powder(2)}, typename DefaultLaw::Material{}, test::no_gravity(1e-6), geometry::Scene{});
  int refused = 0;
  std::apply(
      [&](const auto& default_row, const auto&... others) {
        (
            [&](const auto& r) {
              io::ArchiveReader rd(checkpoint_of(r, 10), std::string(r.name));
              try {
                first.load(rd);
                ADD_FAILURE() << "a " << r.name << " checkpoint was loaded by a " << default_row.name << " solver";
              } catch (const Error& e) {
                std::printf("[ registry ] %s\n", e.what());
                EXPECT_NE(std::string(e.what()).find(fmt::format("\"{}\", the case uses \"{}\"", r.name,
                                                                 default_row.name)),
                          std::string::npos);
                ++refused;
              }
            }(others),
            ...);
      },
      contact::kContactLaws);
  EXPECT_EQ(refused, static_cast<int>(contact::kContactLawCount) - 1);
}

}  // namespace
}  // namespace cgdem
