#include "io/particle_csv.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include "io/atomic_file.hpp"

namespace cgdem::io {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> out;
  size_t start = 0;
  while (true) {
    size_t comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// Column indices in the header; -1 = absent.
struct Layout {
  int x = -1, y = -1, z = -1, d = -1, vx = -1, vy = -1, vz = -1, wx = -1, wy = -1, wz = -1;
  int id = -1, species = -1;
  size_t ncol = 0;
};

class Parser {
 public:
  explicit Parser(const std::string& name) : name_(name) {}

  [[noreturn]] void fail(size_t line, const std::string& what) const {
    throw Error(name_ + ":" + std::to_string(line) + ": " + what);
  }

  Layout header(std::string_view text, size_t line) const {
    const std::map<std::string_view, int Layout::*> known = {
        {"x", &Layout::x},   {"y", &Layout::y},   {"z", &Layout::z},   {"d", &Layout::d},
        {"vx", &Layout::vx}, {"vy", &Layout::vy}, {"vz", &Layout::vz}, {"wx", &Layout::wx},
        {"wy", &Layout::wy}, {"wz", &Layout::wz}, {"id", &Layout::id}, {"species", &Layout::species}};
    Layout L;
    auto names = split_fields(text);
    L.ncol = names.size();
    for (size_t c = 0; c < names.size(); ++c) {
      auto it = known.find(names[c]);
      if (it == known.end())
        fail(line, "unknown column '" + std::string(names[c]) +
                       "' (known: x,y,z,d,vx,vy,vz,wx,wy,wz,id,species)");
      if (L.*(it->second) >= 0) fail(line, "column '" + std::string(names[c]) + "' appears twice");
      L.*(it->second) = static_cast<int>(c);
    }
    for (auto [col, nm] : {std::pair{L.x, "x"}, {L.y, "y"}, {L.z, "z"}, {L.d, "d"}})
      if (col < 0) fail(line, std::string("missing required column '") + nm + "'");
    auto all_or_none = [&](int a, int b, int c, const char* what) {
      int n = (a >= 0) + (b >= 0) + (c >= 0);
      if (n != 0 && n != 3) fail(line, std::string("columns ") + what + " must be given all three or none");
    };
    all_or_none(L.vx, L.vy, L.vz, "vx,vy,vz");
    all_or_none(L.wx, L.wy, L.wz, "wx,wy,wz");
    return L;
  }

  double number(std::string_view f, const char* col, size_t line) const {
    if (f.size() > 1 && f.front() == '+') f.remove_prefix(1);  // from_chars rejects '+'
    double v = 0;
    auto [p, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || ec != std::errc() || p != f.data() + f.size())
      fail(line, std::string("column '") + col + "': '" + std::string(f) + "' is not a number");
    if (!std::isfinite(v)) fail(line, std::string("column '") + col + "': value is " + std::string(f) + " (must be finite)");
    return v;
  }

  template <class Int>
  Int integer(std::string_view f, const char* col, size_t line) const {
    Int v = 0;
    auto [p, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || ec != std::errc() || p != f.data() + f.size())
      fail(line, std::string("column '") + col + "': '" + std::string(f) + "' is not an integer");
    return v;
  }

  void row(std::string_view text, size_t line, const Layout& L, ParticleTable& t) const {
    auto f = split_fields(text);
    if (f.size() != L.ncol)
      fail(line, "expected " + std::to_string(L.ncol) + " fields (as in the header), found " +
                     std::to_string(f.size()));
    t.x.push_back({number(f[L.x], "x", line), number(f[L.y], "y", line), number(f[L.z], "z", line)});
    double d = number(f[L.d], "d", line);
    if (!(d > 0)) fail(line, "column 'd': diameter must be > 0, got " + std::string(f[L.d]));
    t.d.push_back(d);
    if (L.vx >= 0) t.v.push_back({number(f[L.vx], "vx", line), number(f[L.vy], "vy", line), number(f[L.vz], "vz", line)});
    if (L.wx >= 0) t.omega.push_back({number(f[L.wx], "wx", line), number(f[L.wy], "wy", line), number(f[L.wz], "wz", line)});
    t.id.push_back(L.id >= 0 ? integer<int64_t>(f[L.id], "id", line) : static_cast<int64_t>(t.id.size()));
    int s = L.species >= 0 ? integer<int>(f[L.species], "species", line) : 0;
    if (s < 0) fail(line, "column 'species': must be >= 0, got " + std::to_string(s));
    t.species.push_back(s);
  }

 private:
  const std::string& name_;
};

}  // namespace

ParticleTable parse_particles_csv(const std::string& text, const std::string& name) {
  Parser P(name);
  ParticleTable t;
  Layout L;
  bool have_header = false;
  size_t line_no = 0, pos = 0;
  std::unordered_map<int64_t, size_t> line_of_id;  // particle ids must be unique
  while (pos < text.size()) {
    size_t nl = text.find('\n', pos);
    std::string_view line(text.data() + pos, (nl == std::string::npos ? text.size() : nl) - pos);
    pos = nl == std::string::npos ? text.size() : nl + 1;
    ++line_no;
    std::string_view s = trim(line);
    if (s.empty() || s.front() == '#') continue;
    if (!have_header) {
      L = P.header(s, line_no);
      have_header = true;
    } else {
      P.row(s, line_no, L, t);
      auto [it, fresh] = line_of_id.emplace(t.id.back(), line_no);
      if (!fresh)
        P.fail(line_no, "column 'id': " + std::to_string(t.id.back()) + " already used on line " +
                            std::to_string(it->second));
    }
  }
  if (!have_header) throw Error(name + ":" + std::to_string(line_no + 1) + ": missing header line (e.g. 'x,y,z,d')");
  t.validate(name);
  return t;
}

ParticleTable read_particles_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open particle file '" + path + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error("error reading particle file '" + path + "'");
  return parse_particles_csv(ss.str(), path);
}

std::string format_particles_csv(const ParticleTable& t) {
  t.validate();
  std::string out = "id,species,x,y,z,d";
  if (t.has_velocity()) out += ",vx,vy,vz";
  if (t.has_omega()) out += ",wx,wy,wz";
  out += '\n';
  char buf[64];
  auto num = [&](double v) {
    std::snprintf(buf, sizeof buf, ",%.17g", v);
    out += buf;
  };
  for (size_t i = 0; i < t.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%lld,%d", static_cast<long long>(t.id[i]), t.species[i]);
    out += buf;
    num(t.x[i].x), num(t.x[i].y), num(t.x[i].z), num(t.d[i]);
    if (t.has_velocity()) num(t.v[i].x), num(t.v[i].y), num(t.v[i].z);
    if (t.has_omega()) num(t.omega[i].x), num(t.omega[i].y), num(t.omega[i].z);
    out += '\n';
  }
  return out;
}

void write_particles_csv(const std::string& path, const ParticleTable& table) {
  write_file_atomic(path, format_particles_csv(table));
}

}  // namespace cgdem::io
