// Per-phase wall-clock timers. A PhaseTimers object is owned by a solver (no globals);
// `auto t = timers.scope("contacts");` times a block, and table() prints the
// per-phase totals and fractions at the end of a run.
#pragma once
#include <chrono>
#include <map>
#include <string>
#include <vector>

namespace cgdem {

class PhaseTimers {
 public:
  class Scope {
   public:
    Scope(PhaseTimers& t, int id) : t_(t), id_(id), start_(std::chrono::steady_clock::now()) {}
    ~Scope() { t_.add(id_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count()); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PhaseTimers& t_;
    int id_;
    std::chrono::steady_clock::time_point start_;
  };

  // Phase ids are stable: registering the same name twice returns the same id.
  int id(const std::string& name);
  Scope scope(const std::string& name) { return Scope(*this, id(name)); }
  Scope scope(int id) { return Scope(*this, id); }
  void add(int id, double seconds) { seconds_[id] += seconds; ++calls_[id]; }
  double seconds(const std::string& name) const;
  double total() const;
  // Every phase in the order of registration.
  struct Entry {
    std::string name;
    double seconds;
    long calls;
  };
  std::vector<Entry> entries() const;
  // Table: phase, seconds, calls, percent of the sum of all phases.
  std::string table(const std::string& title = "per-phase time") const;
  void reset();

 private:
  std::vector<std::string> names_;
  std::vector<double> seconds_;
  std::vector<long> calls_;
};

// Seconds since construction.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace cgdem
