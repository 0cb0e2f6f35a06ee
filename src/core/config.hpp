// Reading a case file (TOML, SI units) into typed values with validation.
//
// A Config owns the parsed document. Sections hand out typed values by key; every key
// that is read is marked used, and defaults that were applied are written back into the
// document, so that after parsing
//   * check_unused() rejects any key nobody asked for (typos never pass silently), and
//   * resolved_toml() is the complete configuration the run actually used.
// Every error names the file and line (or the command-line option), the full key path and
// what was expected; a bounded Range states its bound.
#pragma once
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/vec3.hpp"

namespace cgdem {

// Allowed interval for a number; open or closed at each end.
struct Range {
  double lo = -INFINITY, hi = INFINITY;
  bool lo_open = false, hi_open = false;
  static Range positive() { return {0.0, INFINITY, true, false}; }
  static Range non_negative() { return {0.0, INFINITY, false, false}; }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range open_closed(double a, double b) { return {a, b, true, false}; }
  static Range at_least(double a) { return {a, INFINITY, false, false}; }
  static Range any() { return {}; }
  bool contains(double v) const;
  std::string describe() const;
};

class Config;

// One key as a reader asks for it: what `cgdem keys` (the generated key reference,
// docs/case_keys.md) states about it. Taken from the accessor calls themselves, so that the
// reference says what is validated.
struct KeyUse {
  std::string path;           // "particles.species[].density": array elements as []
  std::string type;           // "number", "integer", "boolean", "string", "[x, y, z]", ...
  std::string default_value;  // as written in TOML ("" for a required key)
  std::string allowed;        // the range or the choices ("" for any value of the type)
};

// The keys asked of a Config (Config::log_keys), each once, in the order first asked: a
// key read twice (an optional key read by its required form, a section read by two
// readers) keeps its first use.
class KeyLog {
 public:
  void note(KeyUse u);
  const std::vector<KeyUse>& uses() const { return uses_; }

 private:
  std::vector<KeyUse> uses_;
  std::set<std::string> seen_;
};

// A view on one table of the document (the root or a nested section).
class Section {
 public:
  Section(Config* cfg, std::string path) : cfg_(cfg), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  std::string key_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  bool has(const std::string& key) const;

  // Required values (error if missing or of the wrong type or out of range).
  double number(const std::string& key, Range r = Range::any()) const;
  long integer(const std::string& key, Range r = Range::any()) const;
  bool boolean(const std::string& key) const;
  std::string string(const std::string& key, const std::vector<std::string>& choices = {}) const;
  Vec3 vec3(const std::string& key) const;
  std::vector<double> numbers(const std::string& key, Range r = Range::any()) const;
  std::vector<Vec3> vec3_list(const std::string& key) const;  // [[x,y,z], ...]

  // Optional values: the default is applied and recorded in the resolved configuration.
  double number_or(const std::string& key, double def, Range r = Range::any()) const;
  long integer_or(const std::string& key, long def, Range r = Range::any()) const;
  bool boolean_or(const std::string& key, bool def) const;
  std::string string_or(const std::string& key, const std::string& def,
                        const std::vector<std::string>& choices = {}) const;
  Vec3 vec3_or(const std::string& key, Vec3 def) const;
  std::vector<double> numbers_or(const std::string& key, std::vector<double> def,
                                 Range r = Range::any()) const;

  // Sub-tables and arrays of tables.
  Section section(const std::string& key) const;                  // required
  std::optional<Section> optional_section(const std::string& key) const;
  std::vector<Section> sections(const std::string& key) const;    // [[key]]; empty if absent

  // Raise a ConfigError about `key` of this section.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

 private:
  // Records the key's use in the Config's KeyLog, if it has one.
  void note(const std::string& key, const char* type, const std::string& def, const std::string& allowed) const;

  Config* cfg_;
  std::string path_;
};

class Config {
 public:
  // Parse a file; throws ConfigError with the parser's message on a syntax error.
  static Config from_file(const std::string& filename);
  static Config from_string(const std::string& text, const std::string& name = "<string>");
  Config(Config&&) noexcept;
  Config& operator=(Config&&) noexcept;
  ~Config();

  // `--set a.b.c=value`: value is parsed as TOML (number, bool, array, quoted string);
  // anything that does not parse is taken as a bare string. An error about an overridden
  // key names the command line (`--set 'a.b.c=value'`), not the file.
  void apply_override(const std::string& assignment);
  // Sets the string at `path` (e.g. output.dir from --output); `origin` names the option
  // in error messages, e.g. "--output 'DIR'".
  void override_string(const std::string& path, const std::string& value, const std::string& origin);

  Section root() { return Section(this, ""); }
  const std::string& filename() const { return filename_; }

  // Throws ConfigError listing every key that was never read, each with its line and, when
  // a known key of the same table is close (edit distance), "did you mean".
  void check_unused() const;
  // Where the value at `path` came from, for messages: "FILE:LINE" (the key's line, or the
  // line of the nearest enclosing table when the key is absent), "command line (--set
  // 'a.b=v')" for an override, or "FILE" when no line is known.
  std::string origin(const std::string& path) const;
  // The configuration with defaults filled in, as TOML text.
  std::string resolved_toml() const;
  // Every key asked from now on is noted in `log` (null: none), which must outlive the
  // reading.
  void log_keys(KeyLog* log) { key_log_ = log; }

 private:
  friend class Section;
  Config();
  struct Doc;
  std::unique_ptr<Doc> doc_;
  std::string filename_;
  std::set<std::string> used_;
  std::map<std::string, std::string> overrides_;  // key path -> the option that set it
  KeyLog* key_log_ = nullptr;
};

}  // namespace cgdem
