#include "scaling/plot_script.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace cgdem::scaling {
namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string python_with_matplotlib() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("CGDEM_PYTHON")) candidates.emplace_back(env);
  candidates.emplace_back("python3");
  candidates.emplace_back("/usr/bin/python3");
  for (const auto& py : candidates)
    if (std::system((shell_quote(py) + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0) return py;
  return "";
}

}  // namespace

std::vector<std::filesystem::path> plot_script_dirs() {
  namespace fs = std::filesystem;
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("CGDEM_SCRIPT_DIR"); env && *env) dirs.emplace_back(env);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path bin = exe.parent_path();
    dirs.push_back(bin.parent_path() / "share" / "cgdem" / "scripts");  // installed: PREFIX/bin/cgdem
    dirs.push_back(bin / "share" / "cgdem" / "scripts");                // build tree: BUILD/cgdem
  }
  return dirs;
}

std::string run_plot_script(const std::string& script, const std::string& dir) {
  std::filesystem::path path;
  std::vector<std::string> tried;
  for (const auto& d : plot_script_dirs()) {
    if (std::filesystem::exists(d / script)) {
      path = d / script;
      break;
    }
    tried.push_back(d.string());
  }
  if (path.empty()) return fmt::format("plot script {} not found in {}", script, fmt::join(tried, ", "));
  const std::string py = python_with_matplotlib();
  if (py.empty())
    return "no python3 with matplotlib ($CGDEM_PYTHON, python3, /usr/bin/python3; apt-get install python3-matplotlib)";
  const std::string cmd = fmt::format("{} {} {}", shell_quote(py), shell_quote(path.string()), shell_quote(dir));
  if (std::system(cmd.c_str()) != 0) return fmt::format("{} failed", cmd);
  return "";
}

}  // namespace cgdem::scaling
