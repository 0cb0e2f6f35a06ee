#include "core/config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <sstream>
#include <toml.hpp>

namespace cgdem {

using Value = toml::basic_value<toml::discard_comments, std::map, std::vector>;

struct Config::Doc {
  Value root;
};

Config::Config() : doc_(std::make_unique<Doc>()) {}
Config::Config(Config&&) noexcept = default;
Config& Config::operator=(Config&&) noexcept = default;
Config::~Config() = default;

namespace {

// A key path such as "walls.body[1].parts[0].min" split into steps.
struct Step {
  std::string key;
  int index = -1;  // >= 0: element of an array of tables
};

std::vector<Step> split_path(const std::string& path) {
  std::vector<Step> steps;
  std::string item;
  std::istringstream is(path);
  while (std::getline(is, item, '.')) {
    Step s;
    auto br = item.find('[');
    if (br != std::string::npos) {
      s.key = item.substr(0, br);
      s.index = std::stoi(item.substr(br + 1));
    } else {
      s.key = item;
    }
    steps.push_back(s);
  }
  return steps;
}

// Returns the value at `path`, or nullptr. With create=true, missing tables are created.
Value* lookup(Value& root, const std::string& path, bool create) {
  Value* v = &root;
  if (path.empty()) return v;
  for (const Step& s : split_path(path)) {
    if (!v->is_table()) return nullptr;
    auto& t = v->as_table();
    auto it = t.find(s.key);
    if (it == t.end()) {
      if (!create || s.index >= 0) return nullptr;
      it = t.emplace(s.key, Value(Value::table_type{})).first;
    }
    v = &it->second;
    if (s.index >= 0) {
      if (!v->is_array() || s.index >= static_cast<int>(v->as_array().size())) return nullptr;
      v = &v->as_array()[s.index];
    }
  }
  return v;
}

std::string type_name(const Value& v) {
  switch (v.type()) {
    case toml::value_t::boolean: return "a boolean";
    case toml::value_t::integer: return "an integer";
    case toml::value_t::floating: return "a number";
    case toml::value_t::string: return "a string";
    case toml::value_t::array: return "an array";
    case toml::value_t::table: return "a table";
    default: return "a date/time";
  }
}

std::string show(const Value& v) {
  std::ostringstream os;
  if (v.is_table()) return "a table";
  os << v;
  std::string s = os.str();
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

std::string fmt_num(double v) { return fmt::format("{:g}", v); }

void collect_leaves(const Value& v, const std::string& path, std::vector<std::string>& out) {
  if (v.is_table()) {
    for (const auto& [k, child] : v.as_table()) collect_leaves(child, path.empty() ? k : path + "." + k, out);
  } else if (v.is_array() && !v.as_array().empty() && v.as_array().front().is_table()) {
    const auto& a = v.as_array();
    for (size_t i = 0; i < a.size(); ++i) collect_leaves(a[i], fmt::format("{}[{}]", path, i), out);
  } else {
    out.push_back(path);
  }
}

}  // namespace

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Range::describe() const {
  if (std::isinf(lo) && std::isinf(hi)) return "a finite number";
  if (std::isinf(hi)) return fmt::format("a number {} {}", lo_open ? ">" : ">=", fmt_num(lo));
  if (std::isinf(lo)) return fmt::format("a number {} {}", hi_open ? "<" : "<=", fmt_num(hi));
  return fmt::format("a number in {}{}, {}{}", lo_open ? "(" : "[", fmt_num(lo), fmt_num(hi), hi_open ? ")" : "]");
}

// ---------------------------------------------------------------- Config

Config Config::from_file(const std::string& filename) {
  Config c;
  c.filename_ = filename;
  try {
    c.doc_->root = toml::parse<toml::discard_comments, std::map, std::vector>(filename);
  } catch (const std::exception& e) {
    throw ConfigError(fmt::format("{}: cannot read the case file: {}", filename, e.what()));
  }
  return c;
}

Config Config::from_string(const std::string& text, const std::string& name) {
  Config c;
  c.filename_ = name;
  std::istringstream is(text);
  try {
    c.doc_->root = toml::parse<toml::discard_comments, std::map, std::vector>(is, name);
  } catch (const std::exception& e) {
    throw ConfigError(fmt::format("{}: cannot parse: {}", name, e.what()));
  }
  return c;
}

void Config::apply_override(const std::string& assignment) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError(fmt::format("--set '{}': expected key.path=value", assignment));
  std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  Value parsed;
  try {
    std::istringstream is("v = " + text);
    parsed = toml::find(toml::parse<toml::discard_comments, std::map, std::vector>(is, "--set"), "v");
  } catch (const std::exception&) {
    parsed = Value(text);  // a bare word: take it as a string
  }
  auto dot = path.rfind('.');
  std::string parent = dot == std::string::npos ? "" : path.substr(0, dot);
  std::string key = dot == std::string::npos ? path : path.substr(dot + 1);
  Value* table = lookup(doc_->root, parent, /*create=*/true);
  if (!table || !table->is_table())
    throw ConfigError(fmt::format("--set '{}': '{}' is not a table in {}", assignment, parent, filename_));
  table->as_table()[key] = parsed;
}

void Config::check_unused() const {
  std::vector<std::string> leaves, unknown;
  collect_leaves(doc_->root, "", leaves);
  for (const auto& k : leaves)
    if (!used_.count(k)) unknown.push_back(k);
  if (unknown.empty()) return;
  std::string msg = fmt::format("{}: unknown key{} (not used by this case; check the spelling):", filename_,
                                unknown.size() > 1 ? "s" : "");
  for (const auto& k : unknown) msg += "\n  " + k;
  throw ConfigError(msg);
}

std::string Config::resolved_toml() const {
  std::ostringstream os;
  os << doc_->root;
  return os.str();
}

// ---------------------------------------------------------------- Section

namespace {
Value& value_of(Value& root, const std::string& path) {
  Value* v = lookup(root, path, false);
  if (!v) throw std::logic_error("config: section vanished: " + path);
  return *v;
}
}  // namespace

namespace {
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}
}  // namespace

void Section::fail(const std::string& key, const std::string& what) const {
  std::string hint;
  if (what.rfind("missing", 0) == 0) {  // a misspelt key is the usual cause: name it
    Value* t = lookup(cfg_->doc_->root, path_, false);
    if (t && t->is_table())
      for (const auto& [k, v] : t->as_table())
        if (k != key && edit_distance(k, key) <= 2) hint += fmt::format(" (found '{}': misspelt?)", key_path(k));
  }
  throw ConfigError(fmt::format("{}: key '{}': {}{}", cfg_->filename_, key_path(key), what, hint));
}

bool Section::has(const std::string& key) const {
  Value* t = lookup(cfg_->doc_->root, path_, false);
  return t && t->is_table() && t->as_table().count(key);
}

// Fetch a present value and mark it used; nullptr if absent.
static const Value* fetch(Config* cfg, Value& root, const Section& s, const std::string& key,
                          std::set<std::string>& used) {
  (void)cfg;
  Value* t = lookup(root, s.path(), false);
  if (!t || !t->is_table()) return nullptr;
  auto it = t->as_table().find(key);
  if (it == t->as_table().end()) return nullptr;
  used.insert(s.key_path(key));
  return &it->second;
}

static void store_default(Value& root, const Section& s, const std::string& key, Value v,
                          std::set<std::string>& used) {
  Value* t = lookup(root, s.path(), true);
  if (t && t->is_table()) t->as_table()[key] = std::move(v);
  used.insert(s.key_path(key));
}

static double as_number(const Section& s, const std::string& key, const Value& v, const Range& r) {
  double x;
  if (v.is_floating()) x = v.as_floating();
  else if (v.is_integer()) x = static_cast<double>(v.as_integer());
  else s.fail(key, fmt::format("expected {}, got {} ({})", r.describe(), type_name(v), show(v)));
  if (!std::isfinite(x) || !r.contains(x)) s.fail(key, fmt::format("expected {}, got {}", r.describe(), show(v)));
  return x;
}

double Section::number(const std::string& key, Range r) const {
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, fmt::format("missing (required: {})", r.describe()));
  return as_number(*this, key, *v, r);
}

double Section::number_or(const std::string& key, double def, Range r) const {
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) {
    store_default(cfg_->doc_->root, *this, key, Value(def), cfg_->used_);
    return def;
  }
  return as_number(*this, key, *v, r);
}

static long as_integer(const Section& s, const std::string& key, const Value& v, const Range& r) {
  if (!v.is_integer()) s.fail(key, fmt::format("expected an integer, got {} ({})", type_name(v), show(v)));
  long x = static_cast<long>(v.as_integer());
  if (!r.contains(static_cast<double>(x)))
    s.fail(key, fmt::format("expected an integer, {}, got {}", r.describe(), x));
  return x;
}

long Section::integer(const std::string& key, Range r) const {
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, "missing (required: an integer)");
  return as_integer(*this, key, *v, r);
}

long Section::integer_or(const std::string& key, long def, Range r) const {
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) {
    store_default(cfg_->doc_->root, *this, key, Value(static_cast<toml::integer>(def)), cfg_->used_);
    return def;
  }
  return as_integer(*this, key, *v, r);
}

bool Section::boolean(const std::string& key) const {
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, "missing (required: true or false)");
  if (!v->is_boolean()) fail(key, fmt::format("expected true or false, got {} ({})", type_name(*v), show(*v)));
  return v->as_boolean();
}

bool Section::boolean_or(const std::string& key, bool def) const {
  if (!has(key)) {
    store_default(cfg_->doc_->root, *this, key, Value(def), cfg_->used_);
    return def;
  }
  return boolean(key);
}

static std::string as_choice(const Section& s, const std::string& key, const Value& v,
                             const std::vector<std::string>& choices) {
  if (!v.is_string()) s.fail(key, fmt::format("expected a string, got {} ({})", type_name(v), show(v)));
  std::string x = v.as_string().str;
  if (!choices.empty() && std::find(choices.begin(), choices.end(), x) == choices.end())
    s.fail(key, fmt::format("expected one of {}, got \"{}\"", fmt::join(choices, ", "), x));
  return x;
}

std::string Section::string(const std::string& key, const std::vector<std::string>& choices) const {
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, choices.empty() ? "missing (required: a string)"
                                    : fmt::format("missing (required: one of {})", fmt::join(choices, ", ")));
  return as_choice(*this, key, *v, choices);
}

std::string Section::string_or(const std::string& key, const std::string& def,
                               const std::vector<std::string>& choices) const {
  if (!has(key)) {
    store_default(cfg_->doc_->root, *this, key, Value(def), cfg_->used_);
    return def;
  }
  return string(key, choices);
}

static std::vector<double> as_numbers(const Section& s, const std::string& key, const Value& v, const Range& r) {
  if (!v.is_array()) s.fail(key, fmt::format("expected an array of numbers, got {} ({})", type_name(v), show(v)));
  std::vector<double> out;
  for (const auto& e : v.as_array()) {
    double x;
    if (e.is_floating()) x = e.as_floating();
    else if (e.is_integer()) x = static_cast<double>(e.as_integer());
    else s.fail(key, fmt::format("expected an array of numbers, found {} ({})", type_name(e), show(e)));
    if (!std::isfinite(x) || !r.contains(x))
      s.fail(key, fmt::format("every element must be {}, got {}", r.describe(), show(e)));
    out.push_back(x);
  }
  return out;
}

std::vector<double> Section::numbers(const std::string& key, Range r) const {
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, "missing (required: an array of numbers)");
  return as_numbers(*this, key, *v, r);
}

std::vector<double> Section::numbers_or(const std::string& key, std::vector<double> def, Range r) const {
  if (!has(key)) {
    Value::array_type a;
    for (double d : def) a.emplace_back(d);
    store_default(cfg_->doc_->root, *this, key, Value(a), cfg_->used_);
    return def;
  }
  return numbers(key, r);
}

Vec3 Section::vec3(const std::string& key) const {
  auto v = numbers(key);
  if (v.size() != 3) fail(key, fmt::format("expected 3 numbers [x, y, z], got {}", v.size()));
  return {v[0], v[1], v[2]};
}

std::vector<Vec3> Section::vec3_list(const std::string& key) const {
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, "missing (required: an array of [x, y, z])");
  if (!v->is_array()) fail(key, fmt::format("expected an array of [x, y, z], got {}", type_name(*v)));
  std::vector<Vec3> out;
  for (const auto& e : v->as_array()) {
    auto xs = as_numbers(*this, key, e, Range::any());
    if (xs.size() != 3) fail(key, fmt::format("every element must be [x, y, z], got {}", show(e)));
    out.push_back({xs[0], xs[1], xs[2]});
  }
  return out;
}

Vec3 Section::vec3_or(const std::string& key, Vec3 def) const {
  if (!has(key)) {
    numbers_or(key, {def.x, def.y, def.z});
    return def;
  }
  return vec3(key);
}

Section Section::section(const std::string& key) const {
  Value* t = lookup(cfg_->doc_->root, path_, false);
  if (!t || !t->is_table() || !t->as_table().count(key)) fail(key, "missing section");
  if (!t->as_table().at(key).is_table())
    fail(key, fmt::format("expected a table [{}], got {}", key_path(key), type_name(t->as_table().at(key))));
  return Section(cfg_, key_path(key));
}

std::optional<Section> Section::optional_section(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return section(key);
}

std::vector<Section> Section::sections(const std::string& key) const {
  std::vector<Section> out;
  if (!has(key)) return out;
  Value& v = value_of(cfg_->doc_->root, key_path(key));
  if (!v.is_array() || (!v.as_array().empty() && !v.as_array().front().is_table()))
    fail(key, fmt::format("expected an array of tables [[{}]], got {}", key_path(key), type_name(v)));
  for (size_t i = 0; i < v.as_array().size(); ++i) {
    if (!v.as_array()[i].is_table()) fail(key, "every element must be a table");
    out.emplace_back(cfg_, fmt::format("{}[{}]", key_path(key), i));
  }
  if (v.as_array().empty()) cfg_->used_.insert(key_path(key));
  return out;
}

}  // namespace cgdem
