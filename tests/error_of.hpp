// The message of the cgdem::Error that f() throws, or "(no error)" when it throws none, for
// tests that check what a bad input is told.
#pragma once
#include <string>

#include "core/error.hpp"

namespace cgdem::test {

inline std::string error_of(auto f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace cgdem::test
