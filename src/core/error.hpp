// Error types. A cgdem::Error carries a message meant for the user; the command line
// prints it and exits non-zero. Programming errors stay asserts.
#pragma once
#include <stdexcept>
#include <string>

namespace cgdem {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Bad input in a configuration file: names the file and the key path.
struct ConfigError : Error {
  using Error::Error;
};

// The simulation itself went wrong (NaN, blow-up, lost particles beyond tolerance).
struct RunError : Error {
  using Error::Error;
};

}  // namespace cgdem
