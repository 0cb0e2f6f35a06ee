#include "core/config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <regex>
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
      const std::string idx = item.substr(br + 1);
      // "name[12]": digits, then ']' at the end (anything else is not a path of ours)
      size_t n = 0;
      while (n < idx.size() && n < 9 && std::isdigit(static_cast<unsigned char>(idx[n]))) ++n;
      if (n == 0 || n + 1 != idx.size() || idx[n] != ']') return {};
      s.index = std::stoi(idx.substr(0, n));
    } else {
      s.key = item;
    }
    if (s.key.empty()) return {};
    steps.push_back(s);
  }
  return steps;
}

// Returns the value at `path`, or nullptr. With create=true, missing tables are created.
Value* lookup(Value& root, const std::string& path, bool create) {
  Value* v = &root;
  if (path.empty()) return v;
  const std::vector<Step> steps = split_path(path);
  if (steps.empty()) return nullptr;  // not a well-formed path
  for (const Step& s : steps) {
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
  std::string s, raw = os.str();
  for (char ch : raw) {  // one line: toml11 prints arrays over several
    if (ch == '\n') ch = ' ';
    if (ch == ' ' && (s.empty() || s.back() == ' ' || s.back() == '[')) continue;
    if (ch == ']' && !s.empty() && s.back() == ' ') s.pop_back();
    if (ch == ']' && !s.empty() && s.back() == ',') s.pop_back();
    s += ch;
  }
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

// The line of a value in the file `filename` (0: not from that file, e.g. a default or an
// override).
unsigned line_of(const Value& v, const std::string& filename) {
  const toml::detail::region_base* reg = toml::detail::get_region(v);
  if (!reg || !reg->is_ok() || reg->name() != filename) return 0;
  const std::string n = reg->line_num();
  if (n.empty() || !std::isdigit(static_cast<unsigned char>(n[0]))) return 0;
  return static_cast<unsigned>(std::stoul(n));
}

// The value as written in the file when known (an integer too large for 64 bits is
// stored saturated), otherwise as TOML.
std::string source_text(const Value& v) {
  const toml::detail::region_base* reg = toml::detail::get_region(v);
  if (reg && reg->is_ok()) return reg->str();
  return show(v);
}

// Control bytes (binary garbage in a file) are shown as '?' in messages.
std::string printable(std::string s) {
  for (char& ch : s)
    if ((static_cast<unsigned char>(ch) < 0x20 && ch != '\n' && ch != '\t') || ch == 0x7f) ch = '?';
  return s;
}

// toml11's message "[error] toml::fn: what\n --> file\n   |\n 3 | line\n..." as
// "FILE:3: cannot read the case file: syntax error: what" and the excerpt below it.
std::string syntax_error_message(const std::string& filename, const std::string& what) {
  std::string first = what.substr(0, what.find('\n')), rest = what.find('\n') == std::string::npos ? "" : what.substr(what.find('\n'));
  static const std::regex prefix(R"(^\[error\] (toml::[A-Za-z_:]+: )?)");
  first = std::regex_replace(first, prefix, "");
  static const std::regex line_re(R"(\n *([0-9]+) \|)");
  std::string where = filename, line;
  // the first excerpt's line; for a key or table defined twice the second definition's
  for (auto it = std::sregex_iterator(rest.begin(), rest.end(), line_re); it != std::sregex_iterator(); ++it) {
    line = (*it)[1].str();
    if (first.find("already exists") == std::string::npos) break;
  }
  if (!line.empty()) where += ":" + line;
  return printable(fmt::format("{}: cannot read the case file: syntax error: {}{}", where, first, rest));
}

// toml11 stores an integer literal beyond 64 bits saturated: such a value was not what
// the file says.
bool saturated(const Value& v) {
  if (!v.is_integer()) return false;
  const auto x = v.as_integer();
  return x == std::numeric_limits<toml::integer>::max() || x == std::numeric_limits<toml::integer>::min();
}

// The keys of `path` split on dots (indices kept: "body[0]").
std::vector<std::string> components(const std::string& path) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream is(path);
  while (std::getline(is, item, '.')) out.push_back(item);
  return out;
}

std::string strip_index(const std::string& c) { return c.substr(0, c.find('[')); }

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
  } catch (const toml::syntax_error& e) {
    throw ConfigError(syntax_error_message(filename, e.what()));
  } catch (const std::exception& e) {
    throw ConfigError(printable(fmt::format("{}: cannot read the case file: {}", filename, e.what())));
  }
  return c;
}

Config Config::from_string(const std::string& text, const std::string& name) {
  Config c;
  c.filename_ = name;
  std::istringstream is(text);
  try {
    c.doc_->root = toml::parse<toml::discard_comments, std::map, std::vector>(is, name);
  } catch (const toml::syntax_error& e) {
    throw ConfigError(syntax_error_message(name, e.what()));
  } catch (const std::exception& e) {
    throw ConfigError(printable(fmt::format("{}: cannot parse: {}", name, e.what())));
  }
  return c;
}

void Config::apply_override(const std::string& assignment) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError(fmt::format("--set '{}': expected key.path=value", assignment));
  std::string path = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (split_path(path).empty() || path.back() == '.' || path.back() == ']')
    throw ConfigError(fmt::format("--set '{}': '{}' is not a key path (names separated by dots, e.g. time.end; "
                                  "an element of an array of tables as particles.insert[0].count)",
                                  assignment, path));
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
    throw ConfigError(fmt::format("command line (--set '{}'): '{}' is not a table in {}", assignment, parent, filename_));
  table->as_table()[key] = parsed;
  overrides_[path] = fmt::format("--set '{}'", assignment);
}

void Config::override_string(const std::string& path, const std::string& value, const std::string& origin) {
  auto dot = path.rfind('.');
  std::string parent = dot == std::string::npos ? "" : path.substr(0, dot);
  Value* table = lookup(doc_->root, parent, /*create=*/true);
  if (!table || !table->is_table())
    throw ConfigError(fmt::format("command line ({}): '{}' is not a table in {}", origin, parent, filename_));
  table->as_table()[dot == std::string::npos ? path : path.substr(dot + 1)] = Value(value);
  overrides_[path] = origin;
}

std::string Config::origin(const std::string& path) const {
  for (std::string p = path;;) {  // an override of the key or of a table above it
    auto it = overrides_.find(p);
    if (it != overrides_.end()) return fmt::format("command line ({})", it->second);
    auto dot = p.rfind('.');
    if (dot == std::string::npos) break;
    p = p.substr(0, dot);
  }
  for (std::string p = path; !p.empty();) {  // the key's line, else its table's
    if (const Value* v = lookup(doc_->root, p, false))
      if (unsigned line = line_of(*v, filename_)) return fmt::format("{}:{}", filename_, line);
    auto cut = p.find_last_of(".[");
    p = cut == std::string::npos ? "" : p.substr(0, cut);
  }
  return filename_;
}

namespace {
size_t edit_distance(const std::string& a, const std::string& b);
}

void Config::check_unused() const {
  std::vector<std::string> leaves, unknown;
  collect_leaves(doc_->root, "", leaves);
  for (const auto& k : leaves)
    if (!used_.count(k)) unknown.push_back(k);
  if (unknown.empty()) return;
  // A prefix of a key path is known when the case read something at or below it.
  auto known = [&](const std::string& prefix) {
    for (auto it = used_.lower_bound(prefix); it != used_.end() && it->compare(0, prefix.size(), prefix) == 0; ++it)
      if (it->size() == prefix.size() || (*it)[prefix.size()] == '.' || (*it)[prefix.size()] == '[') return true;
    return false;
  };
  std::vector<std::string> msgs;
  for (const auto& k : unknown) {
    const Value* v = lookup(doc_->root, k, false);
    if (v && known(k)) {  // a table the case reads, given as a value
      msgs.push_back(fmt::format("{}: key '{}': expected a table [{}], got {} ({})", origin(k), k, k, type_name(*v),
                                 show(*v)));
      continue;
    }
    // The first component nobody read, and the known names beside it.
    const auto parts = components(k);
    std::string parent, hint;
    for (size_t i = 0; i < parts.size(); ++i) {
      const std::string here = parent.empty() ? parts[i] : parent + "." + parts[i];
      if (known(here)) {
        parent = here;
        continue;
      }
      const std::string name = strip_index(parts[i]);
      std::set<std::string> names;  // the known keys of the table `parent`
      const std::string under = parent.empty() ? "" : parent + ".";
      for (auto it = used_.lower_bound(under); it != used_.end() && it->compare(0, under.size(), under) == 0; ++it)
        names.insert(strip_index(components(it->substr(under.size())).front()));
      size_t best = std::max<size_t>(2, name.size() / 3) + 1;
      std::vector<std::string> close;
      for (const auto& n : names) {
        const size_t d = edit_distance(n, name);
        if (d < best) best = d, close.clear();
        if (d == best) close.push_back(under + n);
      }
      if (!close.empty()) hint = fmt::format(" (did you mean '{}'?)", fmt::join(close, "' or '"));
      else if (!names.empty() && names.size() <= 12)
        hint = fmt::format(" (the keys of {} are: {})", parent.empty() ? "the file" : "[" + parent + "]",
                           fmt::join(names, ", "));
      break;
    }
    msgs.push_back(fmt::format("{}: unknown key '{}'{}", origin(k), k, hint));
  }
  if (msgs.size() == 1) throw ConfigError(msgs.front() + "; it is not used by this case: check the spelling");
  std::string msg = fmt::format("{}: {} unknown keys (not used by this case; check the spelling):", filename_, msgs.size());
  for (const auto& m : msgs) msg += "\n  " + m;
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
  throw ConfigError(fmt::format("{}: key '{}': {}{}", cfg_->origin(key_path(key)), key_path(key), what, hint));
}

void KeyLog::note(KeyUse u) {
  if (seen_.insert(u.path).second) uses_.push_back(std::move(u));
}

namespace {

// A key path with the indices of arrays of tables written [] ("a.b[3].c" -> "a.b[].c").
std::string generic_path(const std::string& path) {
  static const std::regex index(R"(\[[0-9]+\])");
  return std::regex_replace(path, index, "[]");
}

// What a Range allows, as the reference states it ("" for any finite number).
std::string allowed_text(const Range& r) {
  const std::string d = r.describe();
  if (std::isinf(r.lo) && std::isinf(r.hi)) return "";
  return d.substr(std::string("a number ").size());  // "> 0", "in (0, 1]"
}

std::string choices_text(const std::vector<std::string>& choices) {
  std::vector<std::string> quoted;
  for (const auto& c : choices) quoted.push_back("\"" + c + "\"");
  return choices.empty() ? "" : "one of " + fmt::format("{}", fmt::join(quoted, ", "));
}

std::string numbers_text(const std::vector<double>& v) {
  std::vector<std::string> parts;
  for (double x : v) parts.push_back(fmt_num(x));
  return "[" + fmt::format("{}", fmt::join(parts, ", ")) + "]";
}

}  // namespace

void Section::note(const std::string& key, const char* type, const std::string& def, const std::string& allowed) const {
  if (cfg_->key_log_) cfg_->key_log_->note({generic_path(key_path(key)), type, def, allowed});
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

[[noreturn]] static void fail_saturated(const Section& s, const std::string& key, const Value& v) {
  s.fail(key, fmt::format("the integer {} does not fit in 64 bits (write a number such as 1e19 if that is meant)",
                          source_text(v)));
}

static double as_number(const Section& s, const std::string& key, const Value& v, const Range& r) {
  if (saturated(v)) fail_saturated(s, key, v);
  double x;
  if (v.is_floating()) x = v.as_floating();
  else if (v.is_integer()) x = static_cast<double>(v.as_integer());
  else s.fail(key, fmt::format("expected {}, got {} ({})", r.describe(), type_name(v), show(v)));
  if (!std::isfinite(x) || !r.contains(x)) s.fail(key, fmt::format("expected {}, got {}", r.describe(), show(v)));
  return x;
}

double Section::number(const std::string& key, Range r) const {
  note(key, "number", "", allowed_text(r));
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, fmt::format("missing (required: {})", r.describe()));
  return as_number(*this, key, *v, r);
}

double Section::number_or(const std::string& key, double def, Range r) const {
  note(key, "number", fmt_num(def), allowed_text(r));
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) {
    store_default(cfg_->doc_->root, *this, key, Value(def), cfg_->used_);
    return def;
  }
  return as_number(*this, key, *v, r);
}

static long as_integer(const Section& s, const std::string& key, const Value& v, const Range& r) {
  if (!v.is_integer()) s.fail(key, fmt::format("expected an integer, got {} ({})", type_name(v), show(v)));
  if (saturated(v)) fail_saturated(s, key, v);
  long x = static_cast<long>(v.as_integer());
  if (!r.contains(static_cast<double>(x)))
    s.fail(key, fmt::format("expected an integer, {}, got {}", r.describe(), x));
  return x;
}

long Section::integer(const std::string& key, Range r) const {
  note(key, "integer", "", allowed_text(r));
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, "missing (required: an integer)");
  return as_integer(*this, key, *v, r);
}

long Section::integer_or(const std::string& key, long def, Range r) const {
  note(key, "integer", std::to_string(def), allowed_text(r));
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) {
    store_default(cfg_->doc_->root, *this, key, Value(static_cast<toml::integer>(def)), cfg_->used_);
    return def;
  }
  return as_integer(*this, key, *v, r);
}

bool Section::boolean(const std::string& key) const {
  note(key, "boolean", "", "");
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, "missing (required: true or false)");
  if (!v->is_boolean()) fail(key, fmt::format("expected true or false, got {} ({})", type_name(*v), show(*v)));
  return v->as_boolean();
}

bool Section::boolean_or(const std::string& key, bool def) const {
  note(key, "boolean", def ? "true" : "false", "");
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
  note(key, "string", "", choices_text(choices));
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, choices.empty() ? "missing (required: a string)"
                                    : fmt::format("missing (required: one of {})", fmt::join(choices, ", ")));
  return as_choice(*this, key, *v, choices);
}

std::string Section::string_or(const std::string& key, const std::string& def,
                               const std::vector<std::string>& choices) const {
  note(key, "string", "\"" + def + "\"", choices_text(choices));
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
    if (saturated(e)) fail_saturated(s, key, e);
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
  note(key, "array of numbers", "", allowed_text(r).empty() ? "" : "each " + allowed_text(r));
  const Value* v = fetch(cfg_, cfg_->doc_->root, *this, key, cfg_->used_);
  if (!v) fail(key, "missing (required: an array of numbers)");
  return as_numbers(*this, key, *v, r);
}

std::vector<double> Section::numbers_or(const std::string& key, std::vector<double> def, Range r) const {
  note(key, "array of numbers", numbers_text(def), allowed_text(r).empty() ? "" : "each " + allowed_text(r));
  if (!has(key)) {
    Value::array_type a;
    for (double d : def) a.emplace_back(d);
    store_default(cfg_->doc_->root, *this, key, Value(a), cfg_->used_);
    return def;
  }
  return numbers(key, r);
}

Vec3 Section::vec3(const std::string& key) const {
  note(key, "[x, y, z]", "", "");
  auto v = numbers(key);
  if (v.size() != 3) fail(key, fmt::format("expected 3 numbers [x, y, z], got {}", v.size()));
  return {v[0], v[1], v[2]};
}

std::vector<Vec3> Section::vec3_list(const std::string& key) const {
  note(key, "array of [x, y, z]", "", "");
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
  note(key, "[x, y, z]", numbers_text({def.x, def.y, def.z}), "");
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
