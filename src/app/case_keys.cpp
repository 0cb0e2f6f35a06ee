#include "app/case_keys.hpp"

#include <fmt/format.h>

#include <map>
#include <set>

#include "app/air_case.hpp"
#include "app/dem_case.hpp"
#include "app/die_diagnostics.hpp"
#include "app/flow_case.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace cgdem::app {

namespace {

// Cases that together take every path through the readers: every optional table, both
// sides of every either-or (insert by count or by solid volume, in a box or in the die's
// cavity; a body moving at a constant velocity or by a velocity table; the four shapes;
// a flow step given as dt or as a Courant number). Their values do not enter the
// reference: a default is the one the reader passes, whatever the case sets.
//
// The [time] and [output] tables of both cases with parcels.
std::string time_and_output(const char* end, const char* dt) {
  return fmt::format("\n[time]\nend = {}\ndt = {}\n\n[output]\ndir = \"out\"\n", end, dt);
}

// The species of both cases with parcels and the head of their first insertion.
const std::string kSpeciesAndInsertion = R"(
[[particles.species]]
name = "powder"
d_original = 125e-6
ratio = 3
density = 1500.0
[[particles.insert]]
species = "powder"
count = 10)";

const std::string kParticleCase = R"(
[particles]
seed = 7
skin = 0.0)" + kSpeciesAndInsertion + R"(
min = [1e-3, 1e-3, 12e-3]
max = [5e-3, 4e-3, 16e-3]
velocity = [0.0, 0.0, 0.0]
[[particles.insert]]
species = "powder"
solid_volume = 1e-9
region = "die_filling_cavity"
[[particles.file]]
path = "bed.csv"
species = "powder"

[contact]
stiffness = 50.0
restitution = 0.9
friction = 0.3
wall_restitution = 0.9
wall_friction = 0.3

[domain]
min = [0.0, 0.0, 0.0]
max = [24e-3, 4.8e-3, 18e-3]
periodic = "none"

[physics]
gravity = [0.0, 0.0, -9.81]

[walls]
sdf_cutoff = 1e-3
[walls.die_filling]
domain_min = [0.0, 0.0, 0.0]
domain_max = [24e-3, 4.8e-3, 18e-3]
table_top = 7.2e-3
mouth_x0 = 10e-3
mouth_length = 6e-3
mouth_y0 = 0.0
mouth_width = 4.8e-3
deep_depth = 4e-3
shallow_depth = 2e-3
cavity_size = [6e-3, 4.8e-3, 6e-3]
cavity_x0 = 10e-3
shoe_wall = 3e-3
[[walls.body]]
name = "fixed"
velocity = [0.0, 0.0, 0.0]
[[walls.body.part]]
name = "floor"
type = "box"
min = [0.0, 0.0, -1e-3]
max = [24e-3, 4.8e-3, 0.0]
inside_free = false
[[walls.body.part]]
type = "halfspace"
point = [0.0, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
[[walls.body]]
name = "moving"
times = [0.0, 1e-3]
velocities = [[0.0, 0.0, 0.0], [0.1, 0.0, 0.0]]
[[walls.body.part]]
type = "cylinder"
p0 = [20e-3, 0.0, 15e-3]
p1 = [20e-3, 4.8e-3, 15e-3]
radius = 1e-3
[[walls.body.part]]
type = "sphere"
centre = [22e-3, 2e-3, 16e-3]
radius = 1e-3
[[walls.body.part]]
type = "cone"
p0 = [3e-3, 2e-3, 16e-3]
p1 = [3e-3, 2e-3, 17e-3]
radius0 = 0.0
radius1 = 1e-3
[[walls.body.part]]
type = "ring"
p0 = [8e-3, 2e-3, 1e-3]
p1 = [8e-3, 2e-3, 1.5e-3]
radius_inner = 0.5e-3
radius_outer = 2e-3

[diagnostics]
interval = 1e-3
[[diagnostics.pressure_cell]]
name = "A"
min = [11e-3, 0.0, 4e-3]
max = [12e-3, 4.8e-3, 5e-3]

[air]
enabled = true
dx = 0.6e-3
coupling = "implicit"
[air.implicit]
method = "anderson"
[air.pressure]
method = "pcg-mg2"
[air.boundary]
open_pressure = 0.0

)" + time_and_output("0.04", "1.0e-6");

// The other contact law (src/contact/laws.hpp): its own keys.
const std::string kHertzCase = R"(
[particles]
seed = 7)" + kSpeciesAndInsertion + R"(
min = [1e-3, 1e-3, 1e-3]
max = [5e-3, 4e-3, 5e-3]

[contact]
law = "hertz-mindlin"
youngs_modulus = 5e6
poisson_ratio = 0.3
restitution = 0.9
friction = 0.3
wall_youngs_modulus = 5e6
wall_poisson_ratio = 0.3
max_impact_speed = 1.0

[domain]
min = [0.0, 0.0, 0.0]
max = [6e-3, 5e-3, 6e-3]

)" + time_and_output("1e-3", "1e-7");

// The flow cases, with the step given as dt and as a Courant number.
const std::string kFlowHead = R"(
[flow]
kind = "taylor_green"
n = 16
end = 0.5)";

const std::string kFlowCaseDt = kFlowHead + R"(
dt = 0.05
[flow.pressure]
method = "pcg-fft"
[output]
dir = "out/taylor_green"
)";

const std::string kFlowCaseCfl = kFlowHead + R"(
cfl = 0.5
)";

// The keys the readers ask of the built-in cases, each once.
std::vector<KeyUse> keys_of(const std::vector<std::string>& cases) {
  KeyLog log;
  for (const std::string& text : cases) {
    Config cfg = Config::from_string(text, "the built-in case of the key reference");
    cfg.log_keys(&log);
    read_case(cfg);
  }
  return log.uses();
}

// The table a key belongs to, as a case file writes its heading.
std::string heading(const std::string& path) {
  std::string table = path.substr(0, path.rfind('.'));
  const bool array = table.size() > 2 && table.substr(table.size() - 2) == "[]";
  std::string name;
  for (char ch : table)
    if (ch != '[' && ch != ']') name += ch;
  return array ? "[[" + name + "]]" : "[" + name + "]";
}

std::string cell(std::string s) {
  for (size_t i = s.find('|'); i != std::string::npos; i = s.find('|', i + 2)) s.replace(i, 1, "\\|");
  return s;
}

// One table per heading, in the order the readers first reach them, the keys of each in
// the order they are asked for.
std::string tables(const std::vector<KeyUse>& uses, const std::map<std::string, KeyDoc>& docs) {
  std::vector<std::string> order;
  std::map<std::string, std::string> rows;
  for (const KeyUse& u : uses) {
    const KeyDoc& d = docs.at(u.path);
    const std::string h = heading(u.path);
    if (!rows.count(h)) order.push_back(h);
    const std::string def =
        d.default_note ? d.default_note : (u.default_value.empty() ? "required" : "`" + u.default_value + "`");
    rows[h] += fmt::format("| `{}` | {} | {} | {} | {} | {} |\n", u.path.substr(u.path.rfind('.') + 1), u.type,
                           *d.unit ? d.unit : "-", cell(def), cell(u.allowed.empty() ? "any" : u.allowed),
                           cell(d.meaning));
  }
  std::string out;
  for (const std::string& h : order)
    out += fmt::format("\n### {}\n\n| key | type | unit | default | allowed | meaning |\n|---|---|---|---|---|---|\n{}",
                       h, rows[h]);
  return out;
}

const char* kIntro = R"(# Case file keys

<!-- Generated by `cgdem keys` (src/app/case_keys.cpp) from the case readers; do not edit:
     the test docs.case_keys_up_to_date fails when this file differs from the output. -->

A case is one TOML file in SI units. Every key is validated when the case is read
(`cgdem run CASE.toml --check` reads and validates the whole case, builds the walls and
inserts the parcels, and exits without stepping or writing anything). A bad value stops
with the file, the line and the key, what was expected and the bound:

    cgdem: error: case.toml:8: key 'particles.species[0].density': expected a number in (0, 100000], got 1e+06
    cgdem: error: command line (--set 'contact.restitution=2'): key 'contact.restitution': expected a number in (0, 1], got 2
    cgdem: error: case.toml:38: unknown key 'output.energy_intervall' (did you mean 'output.energy_interval'?); it is not used by this case: check the spelling
    cgdem: error: case.toml:19: cannot read the case file: syntax error: value ("friction") already exists.

A value set with `--set` (or the folder given with `--output`) is reported as the command
line's, not the file's. An integer too large for 64 bits is refused (TOML readers would
otherwise store it saturated). NaN and infinities are never accepted.

The upper bounds are there to catch a mistyped exponent before it becomes an overflow, a
run that never ends or an allocation that fails; they are far outside any physical case.

Below, every key as its reader asks for it: its type, its default (or `required`), the
values the reader accepts ("any": every finite number, every string) and, from the table
beside the readers, its unit and meaning. Some keys are read only with others (the
meaning says which); a key the case does not use is refused.
)";

}  // namespace

void read_case(Config& cfg) {
  if (is_flow_case(cfg)) {
    read_flow_case(cfg);
    return;
  }
  const DemCase c = read_dem_case(cfg);
  read_air_case(cfg, c.dem);
  read_diagnostics(cfg);
}

std::vector<KeyUse> keys_read(Config& cfg) {
  KeyLog log;
  cfg.log_keys(&log);
  read_case(cfg);
  cfg.log_keys(nullptr);
  return log.uses();
}

std::string case_key_reference() {
  const std::vector<KeyUse> particles = keys_of({kParticleCase, kHertzCase});
  const std::vector<KeyUse> flow = keys_of({kFlowCaseDt, kFlowCaseCfl});
  std::map<std::string, KeyDoc> docs;
  for (const KeyDoc& d : case_key_docs())
    if (!docs.emplace(d.path, d).second) throw Error(fmt::format("key reference: '{}' is described twice", d.path));
  std::set<std::string> read;
  std::vector<std::string> missing, unread;
  for (const auto* uses : {&particles, &flow})
    for (const KeyUse& u : *uses) {
      read.insert(u.path);
      if (!docs.count(u.path)) missing.push_back(u.path);
    }
  for (const auto& [path, d] : docs)
    if (!read.count(path)) unread.push_back(path);
  if (!missing.empty() || !unread.empty())
    throw Error(fmt::format("key reference: keys read without a description in case_key_docs.cpp: {}; described "
                            "keys that no reader asks for: {}",
                            missing.empty() ? "none" : fmt::format("{}", fmt::join(missing, ", ")),
                            unread.empty() ? "none" : fmt::format("{}", fmt::join(unread, ", "))));
  return std::string(kIntro) + "\n## Cases with parcels\n" + tables(particles, docs) +
         "\n## Flow cases ([flow], no parcels)\n" + tables(flow, docs);
}

std::vector<std::string> undocumented_keys(const std::string& case_file) {
  Config cfg = Config::from_file(case_file);
  std::set<std::string> described;
  for (const KeyDoc& d : case_key_docs()) described.insert(d.path);
  std::vector<std::string> out;
  for (const KeyUse& u : keys_read(cfg))
    if (!described.count(u.path)) out.push_back(u.path);
  return out;
}

int keys_command(const std::string& output, const std::vector<std::string>& check) {
  if (!check.empty()) {
    int status = 0;
    for (const std::string& f : check)
      if (const auto keys = undocumented_keys(f); !keys.empty()) {
        fmt::print("{}: keys without an entry in the key reference: {}\n", f, fmt::join(keys, ", "));
        status = 1;
      }
    if (status == 0) fmt::print("every key of the {} case(s) is in the key reference\n", check.size());
    return status;
  }
  const std::string reference = case_key_reference();
  if (output.empty())
    fmt::print("{}", reference);
  else
    io::write_file_atomic(output, reference);
  return 0;
}

}  // namespace cgdem::app
