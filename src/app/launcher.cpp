#include "app/launcher.hpp"

#include <fmt/format.h>

#include <cstdlib>

#include "core/error.hpp"

namespace cgdem::app {

namespace {

// A positive integer from the environment, or 0 when unset or not a number.
int env_int(const char* name) {
  const char* s = std::getenv(name);
  if (!s || !*s) return 0;
  char* end = nullptr;
  const long v = std::strtol(s, &end, 10);
  return (*end == '\0' && v > 0 && v < (1L << 30)) ? static_cast<int>(v) : 0;
}

}  // namespace

LaunchedAs launched_as() {
  static constexpr const char* kVars[][2] = {
      {"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"}, {"PMI_SIZE", "PMI_RANK"}, {"SLURM_NTASKS", "SLURM_PROCID"}};
  for (const auto& v : kVars) {
    const int size = env_int(v[0]);
    if (size > 0) {
      const char* r = std::getenv(v[1]);
      return {size, r ? std::atoi(r) : 0, v[0]};
    }
  }
  return {};
}

void require_single_process(const LaunchedAs& l, const std::string& command) {
  if (l.size <= 1) return;
  throw Error(fmt::format(
      "`cgdem {}` was started as {} processes ({}={}), but it runs in one process: each copy would run the "
      "whole case and write the same output folder. Start it without an MPI launcher (or with -np 1) and give it "
      "the cores as OpenMP threads (--threads N); only `cgdem run` runs over MPI ranks (in a build with MPI)",
      command, l.size, l.variable, l.size));
}

}  // namespace cgdem::app
