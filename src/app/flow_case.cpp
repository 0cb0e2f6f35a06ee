#include "app/flow_case.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "core/error.hpp"
#include "core/revision.hpp"
#include "core/timers.hpp"
#include "fluid/taylor_green.hpp"
#include "geometry/scene.hpp"
#include "io/atomic_file.hpp"
#include "io/metrics.hpp"
#include "solvers/fluid/fluid_solver.hpp"
#include "solvers/pressure/pressure_solver.hpp"
#include "solvers/run/run_driver.hpp"

namespace cgdem::app {

namespace {

constexpr double kMaxFlowSteps = 1e9;

// The fixed step from exactly one of flow.dt (end a whole number of steps) and flow.cfl (a
// fraction of the explicit limit), at most kMaxFlowSteps steps and within the explicit limit
// of the air solver. Reads c.grid, c.amplitude, c.t_end and c.fluid; writes c.dt and c.steps.
void resolve_step(const Section& s, FlowCase& c) {
  const fluid::FluidParams& f = c.fluid;
  const double dx = c.grid.dx;
  const bool has_dt = s.has("dt"), has_cfl = s.has("cfl");
  if (has_dt == has_cfl) s.fail(has_dt ? "cfl" : "dt", "give exactly one of flow.dt and flow.cfl");
  if (has_dt) {
    c.dt = s.number("dt", Range::open_closed(0, 1e6));
    const double steps = c.t_end / c.dt;
    if (!(steps <= kMaxFlowSteps))
      s.fail("dt", fmt::format("flow.end / flow.dt = {:.3g} steps, more than {:g}", steps, kMaxFlowSteps));
    c.steps = std::lround(steps);
    if (c.steps < 1 || std::fabs(steps - c.steps) > 1e-9 * steps)
      s.fail("dt", fmt::format("flow.end = {:g} s is not a whole number of steps of {:g} s", c.t_end, c.dt));
  }
  const double dt_adv = dx / (2 * c.amplitude), dt_visc = dx * dx * f.rho / (6 * f.mu);
  if (has_cfl) {
    const double cfl = s.number("cfl", Range::open_closed(0, 1));
    const double steps = std::ceil(c.t_end / (cfl * std::min(dt_adv, dt_visc)) - 1e-9);
    if (!(steps <= kMaxFlowSteps))
      s.fail("cfl", fmt::format("flow.end = {:g} s takes {:.3g} steps at this Courant number, more than {:g}", c.t_end,
                                steps, kMaxFlowSteps));
    c.steps = static_cast<long>(steps);
    c.dt = c.t_end / c.steps;
  }
  if (c.dt > dt_adv * (1 + 1e-12) || c.dt > dt_visc * (1 + 1e-12))
    s.fail(has_dt ? "dt" : "cfl",
           fmt::format("the step {:g} s exceeds the explicit limit of the air solver on {} cells: {:g} s (Courant "
                       "number 2 U0 dt/dx = 1: {:g} s; viscous dx^2 rho/(6 mu): {:g} s)",
                       c.dt, c.n, std::min(dt_adv, dt_visc), dt_adv, dt_visc));
}

}  // namespace

bool is_flow_case(Config& cfg) { return cfg.root().has("flow"); }

FlowCase read_flow_case(Config& cfg) {
  FlowCase c;
  Section s = cfg.root().section("flow");
  c.kind = s.string("kind", {"taylor_green"});
  c.n = static_cast<int>(s.integer("n", Range::closed(4, 4096)));
  c.length = s.number_or("length", 2 * M_PI, Range::open_closed(0, 1e3));
  c.amplitude = s.number_or("amplitude", 1.0, Range::open_closed(0, 1e3));
  c.t_end = s.number("end", Range::open_closed(0, 1e6));

  fluid::FluidParams& f = c.fluid;
  f.rho = s.number_or("density", 1.0, Range::open_closed(0, 1e4));
  f.mu = s.number_or("viscosity", 0.05, Range::open_closed(0, 1e2));
  f.time_order = static_cast<int>(s.integer_or("time_order", 2, Range::closed(1, 2)));
  f.advection = fluid::advection_from_string(s.string_or("advection", "van-leer", {"van-leer", "mc", "central", "upwind"}));
  f.bc = fluid::uniform_boundary(fluid::BcType::Periodic);
  Section ps = s.optional_section("pressure").value_or(Section(&cfg, s.key_path("pressure")));
  f.pressure.method = ps.string_or("method", "pcg-fft", pressure::pressure_method_names());
  f.pressure.rel_tol = ps.number_or("tolerance", 1e-11, Range{0, 1, true, true});
  f.pressure.max_iter = static_cast<int>(ps.integer_or("max_iterations", 500, Range::closed(1, 1e6)));
  f.stage_rel_tol = f.pressure.rel_tol;  // the verification solves every stage to the same tolerance
  // The explicit limits without safety factors: a fixed dt is checked against them below.
  f.cfl = 1.0;
  f.visc_safety = 1.0;

  c.grid = {c.n, c.n, 1, c.length / c.n, {0, 0, 0}};
  resolve_step(s, c);
  f.validate();

  Section os = cfg.root().optional_section("output").value_or(Section(&cfg, "output"));
  c.output_dir = os.string_or("dir", "out/taylor_green");
  return c;
}

namespace {

// The flow case's phases of the run driver (solvers/run/run_driver.hpp): fixed steps to
// flow.end, each checked (the pressure solve converged, the velocity finite and not
// runaway), and the errors against the exact solution at the end.
class FlowRun final : public run::Run {
 public:
  FlowRun(const FlowCase& c, const std::string& case_file, const std::string& resolved_config)
      : c_(c), case_file_(case_file), config_(resolved_config), tg_{2 * M_PI / c.length, c.amplitude} {}

  bool set_up() override;
  void check_health() override;
  void write_initial() override {}
  bool finished() const override { return n_ >= c_.steps; }
  void step() override {
    ++n_;
    const double t_next = n_ == c_.steps ? c_.t_end : n_ * c_.dt;
    last_ = solver_->advance(s_, scene_.at(t_next), {}, t_next - s_.t);
    s_.t = t_next;  // no drift of the clock over many steps
  }
  void observe() override { max_div_ = std::max(max_div_, last_.max_divergence); }
  run::Due due() override { return {true, n_ == c_.steps}; }
  void write_due() override {}
  void progress(bool) override {}
  int report() override;

 private:
  const FlowCase& c_;
  std::string case_file_, config_;
  fluid::TaylorGreen tg_;
  Stopwatch clock_;
  std::unique_ptr<fluid::FluidSolver> solver_;
  fluid::FluidState s_;
  geometry::Scene scene_;
  fluid::StepStats last_;
  long n_ = 0;
  double max_div_ = 0;
};

bool FlowRun::set_up() {
  const std::filesystem::path out(c_.output_dir);
  std::filesystem::create_directories(out);
  io::write_file_atomic((out / "config.resolved.toml").string(),
                        fmt::format("# cgdem {} resolved configuration of {}\n{}", kGitRevision, case_file_, config_));
  fmt::print("cgdem {}: taylor-green, {} x {} cells of {:g} m, dt = {:g} s ({} steps to {:g} s), nu = {:g} m^2/s, "
             "time order {}, pressure {} (tol {:g})\n",
             kGitRevision, c_.n, c_.n, c_.grid.dx, c_.dt, c_.steps, c_.t_end, c_.fluid.mu / c_.fluid.rho,
             c_.fluid.time_order, c_.fluid.pressure.method, c_.fluid.pressure.rel_tol);
  solver_ = std::make_unique<fluid::FluidSolver>(c_.grid, c_.fluid);
  s_ = fluid::make_fluid_state(c_.grid);
  fluid::set_taylor_green(s_, tg_, 1.0);
  return false;  // flow cases have no checkpoints
}

void FlowRun::check_health() {
  if (n_ == 0) return;  // the exact field
  if (!last_.pressure_converged)
    throw RunError(fmt::format("step {}, t = {:.6g} s: the pressure solve did not converge (relative residual {:.3g}, "
                               "flow.pressure.tolerance = {:g})",
                               n_, s_.t, last_.pressure_residual, c_.fluid.pressure.rel_tol));
  if (!std::isfinite(last_.cfl) || last_.cfl > 10)
    throw RunError(fmt::format("step {}, t = {:.6g} s: the velocity is non-finite or runaway (Courant number {:.3g})",
                               n_, s_.t, last_.cfl));
}

// Errors against the exact solution at t = end, into metrics.csv.
int FlowRun::report() {
  const double nu = c_.fluid.mu / c_.fluid.rho;
  const double F = tg_.decay(nu, c_.t_end);
  const fluid::TaylorGreenErrors e = fluid::taylor_green_errors(s_, tg_, c_.fluid.rho, F);
  const double ke = e.kinetic_energy, ke_exact = tg_.kinetic_energy(c_.fluid.rho, F);
  const double A = e.decay_factor;
  const io::Metrics m{{"u_error_l2_m_s", e.l2},
                      {"u_error_max_m_s", e.max},
                      {"kinetic_energy_J_m3", ke},
                      {"kinetic_energy_rel_error", (ke - ke_exact) / ke_exact},
                      {"decay_factor", A},
                      {"decay_factor_error", A - F},
                      {"max_divergence_1_s", max_div_},
                      {"dx_m", c_.grid.dx},
                      {"dt_s", c_.dt},
                      {"steps", static_cast<double>(c_.steps)},
                      {"end_time_s", s_.t},
                      {"wall_time_s", clock_.seconds()}};
  io::write_metrics((std::filesystem::path(c_.output_dir) / "metrics.csv").string(), m);
  fmt::print("taylor-green at t = {:g} s: u error rms {:.4e} m/s, max {:.4e} m/s; KE {:.6e} J/m^3 (rel. error {:.3e}); "
             "decay factor {:.10f} (exact {:.10f}); max divergence {:.1e} 1/s; {:.2f} s\n",
             s_.t, e.l2, e.max, ke, (ke - ke_exact) / ke_exact, A, F, max_div_, clock_.seconds());
  fmt::print("results in {}\n", c_.output_dir);
  return 0;
}

}  // namespace

int run_flow_case(const FlowCase& c, const std::string& case_file, const std::string& resolved_config) {
  FlowRun r(c, case_file, resolved_config);
  return run::drive(r);
}

}  // namespace cgdem::app
