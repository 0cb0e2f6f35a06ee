// `cgdem run`: read a case file, apply the command line's overrides, validate every key,
// and run it. Used by main.cpp and in-process by the analysis commands (converge, scale).
#pragma once
#include <string>
#include <vector>

namespace cgdem::app {

struct RunRequest {
  std::string case_file;
  std::vector<std::string> sets;  // key.path=value overrides, applied in order
  std::string output;             // overrides output.dir when not empty
  std::string restart;            // checkpoint to continue from, or empty
  // `cgdem run CASE --check`: read and validate the whole configuration, build the scene
  // and insert the parcels (the air grid's size is checked, not allocated), print a
  // summary and return 0 without stepping or writing anything.
  bool check = false;
  // Over the ranks of MPI_COMM_WORLD (mpi/run_distributed.hpp; builds with CGDEM_MPI,
  // MPI initialised by the caller).
  bool distributed = false;
};

// Returns the process exit status (0 on success). Throws cgdem::Error on bad input and
// RunError when the run has to stop.
int run_case_file(const RunRequest& r);

// The configuration body run_case_file would write to config.resolved.toml (every key
// validated, nothing run): how the analysis commands recognise a finished run.
std::string resolve_case_file(const RunRequest& r);

}  // namespace cgdem::app
