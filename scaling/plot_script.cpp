#include "scaling/plot_script.hpp"

#include <fmt/format.h>

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

std::string run_plot_script(const std::string& script, const std::string& dir) {
  const std::filesystem::path path = std::filesystem::path(__FILE__).parent_path() / script;
  if (!std::filesystem::exists(path)) return fmt::format("plot script {} not found", path.string());
  const std::string py = python_with_matplotlib();
  if (py.empty())
    return "no python3 with matplotlib ($CGDEM_PYTHON, python3, /usr/bin/python3; apt-get install python3-matplotlib)";
  const std::string cmd = fmt::format("{} {} {}", shell_quote(py), shell_quote(path.string()), shell_quote(dir));
  if (std::system(cmd.c_str()) != 0) return fmt::format("{} failed", cmd);
  return "";
}

}  // namespace cgdem::scaling
