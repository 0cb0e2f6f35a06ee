// One full air step on the die-filling grid (default 140 x 70 x 50, dx = 0.6 mm, domain
// 84 x 42 x 30 mm) in a realistic state, timed phase by phase.
//
// Scene: the die-filling walls of src/geometry/die_filling.hpp (type-1 stepped die, shoe
// sliding at 0.1 m/s), taken at t0 = 0.10 s (the shoe half over the die mouth) and MOVING:
// every step sees the scene at its end time, so the IBM fractions are recomputed each step.
// Air: rho = 1 kg/m^3, mu = 1.8e-5 Pa s, gravity -9.81 m/s^2 along z, Wall sides, Open at +z.
// Packed bed (eps = 0.45, d_O = 125 um): the die box x in [37,47], y in [6,36], z in [2,14] mm
// and the shoe cavity (10 x 30 x 10 mm, moving with the shoe); eps of a cell
//   eps = 1 - (1 - 0.45) * (volume fraction of the cell inside a bed box)   (exact overlap),
// so eps^{n+1} != eps^n at the cavity's edges (d(eps)/dt of eq. 12 is exercised).
// Implicit drag coefficient on a face, with E the face eps and a slip of 0.05 m/s:
//   K = beta(E) = (1 - E) * beta/(1-eps)(E)   (coupling/drag.hpp, eqs. 9-10; 0 where E = 1)
//   Kv = K v_p with v_p = the shoe velocity on faces in the cavity bed, 0 in the die.
// Velocity: a smooth 3-D vortex field of amplitude 0.1 m/s, projected by `warmup` untimed
// steps (which also give the pressure its warm start, as in a run). Fluid step dt = 1e-4 s.
// Prints the per-phase table of the timed steps (seconds per step), iterations and
// divergence, and as its last line "fluid-step-s: <mean seconds per step>".
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ctime>

#include "bench/bench.hpp"
#include "core/error.hpp"
#include "core/timers.hpp"
#include "coupling/drag.hpp"
#include "geometry/die_filling.hpp"
#include "solvers/fluid/fluid_solver.hpp"

namespace cgdem::bench {

namespace {
using namespace cgdem::fluid;

constexpr double kEpsBed = 0.45, kDo = 125e-6, kSlip = 0.05;

double process_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// Length of [a0, a1] inside [b0, b1].
double overlap(double a0, double a1, double b0, double b1) { return std::max(0.0, std::min(a1, b1) - std::max(a0, b0)); }

// eps of every cell with the shoe displaced by `shift` along x.
void bed_eps(const MacGrid& g, const geometry::DieFillingParams& p, double shift, Field& eps) {
  const double h = g.dx, vol = h * h * h;
  const Vec3 c0 = p.cavity_lo(), c1 = p.cavity_hi();
  const double zd = p.table_top - p.deep_depth, x1 = p.mouth_x0 + p.mouth_length, y1 = p.mouth_y0 + p.mouth_width;
#pragma omp parallel for schedule(static)
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        const Vec3 lo = g.origin + h * Vec3{double(i), double(j), double(k)};
        const Vec3 hi = lo + Vec3{h, h, h};
        double f = overlap(lo.x, hi.x, p.mouth_x0, x1) * overlap(lo.y, hi.y, p.mouth_y0, y1) *
                   overlap(lo.z, hi.z, zd, p.table_top);
        f += overlap(lo.x, hi.x, c0.x + shift, c1.x + shift) * overlap(lo.y, hi.y, c0.y, c1.y) *
             overlap(lo.z, hi.z, c0.z, c1.z);
        eps(i, j, k) = 1 - (1 - kEpsBed) * std::min(1.0, f / vol);
      }
}

// K = beta(E) and Kv = K v_p on every face from the cell eps (E = mean of the two cells).
void drag_sources(const MacGrid& g, const geometry::DieFillingParams& p, double shift, double v_shoe,
                  const Field& eps, Sources& src) {
  const coupling::AirProperties air{1.0, 1.8e-5};
  const Vec3 c0 = p.cavity_lo(), c1 = p.cavity_hi();
  for (int d = 0; d < 3; ++d) {
    src.K[d] = make_face_field(g, d);
    src.Kv[d] = make_face_field(g, d);
    const std::array<int, 3> e = g.face_extent(d), u = unit(d);
#pragma omp parallel for schedule(static)
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          const int il = std::max(i - u[0], 0), jl = std::max(j - u[1], 0), kl = std::max(k - u[2], 0);
          const int ir = std::min(i, g.nx - 1), jr = std::min(j, g.ny - 1), kr = std::min(k, g.nz - 1);
          const double E = 0.5 * (eps(il, jl, kl) + eps(ir, jr, kr));
          if (E >= 1) continue;
          const double K = (1 - E) * coupling::beta_over_solid(coupling::DragLaw::ErgunWenYu, E, kSlip, kDo, air);
          src.K[d](i, j, k) = K;
          const Vec3 x = g.face_centre(d, i, j, k);
          const bool in_cavity = x.x > c0.x + shift && x.x < c1.x + shift && x.z > c0.z;
          if (d == 0 && in_cavity) src.Kv[d](i, j, k) = K * v_shoe;
        }
  }
}

// Smooth vortex field of amplitude U0 (not divergence-free: the warm-up steps project it).
void vortex(const MacGrid& g, double U0, FluidState& s) {
  const double Lx = g.nx * g.dx, Ly = g.ny * g.dx, Lz = g.nz * g.dx, pi = M_PI;
  for (int d = 0; d < 3; ++d) {
    Field& f = s.vel(d);
    const std::array<int, 3> e = g.face_extent(d);
    for (int k = 0; k < e[2]; ++k)
      for (int j = 0; j < e[1]; ++j)
        for (int i = 0; i < e[0]; ++i) {
          const Vec3 x = g.face_centre(d, i, j, k);
          const double a = pi * x.x / Lx, b = pi * x.y / Ly, c = pi * x.z / Lz;
          f(i, j, k) = d == 0 ? U0 * std::sin(2 * a) * std::cos(b) * std::sin(c)
                       : d == 1 ? -U0 * std::cos(a) * std::sin(2 * b) * std::cos(c)
                                : 0.5 * U0 * std::sin(a) * std::sin(b) * std::sin(2 * c);
        }
  }
}
// max |d(eps)/dt + div(E u)| [1/s] over the cells with some fluid (alpha_cell < 1) and over the
// cells entirely inside walls (where no pressure acts), and where the first maximum is.
struct DivSplit {
  double fluid = 0, solid = 0;
  std::array<int, 3> at{};
};
DivSplit divergence_split(const FluidState& s, const Field& eps_old, const Field& alpha, double dt) {
  const MacGrid& g = s.grid;
  DivSplit r;
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) {
        double div = (s.eps(i, j, k) - eps_old(i, j, k)) / dt;
        for (int d = 0; d < 3; ++d) {
          const std::array<int, 3> e = unit(d);
          auto flux = [&](int a, int b, int c) {
            const double E = 0.5 * (s.eps(a, b, c) + s.eps(a - e[0], b - e[1], c - e[2]));
            return E * s.vel(d)(a, b, c);
          };
          div += (flux(i + e[0], j + e[1], k + e[2]) - flux(i, j, k)) / g.dx;
        }
        if (alpha(i, j, k) < 1) {
          if (std::fabs(div) > r.fluid) r.fluid = std::fabs(div), r.at = {i, j, k};
        } else {
          r.solid = std::max(r.solid, std::fabs(div));
        }
      }
  return r;
}
}  // namespace

int run_fluid_bench(const FluidBenchArgs& args) {
  omp_set_num_threads(args.threads);
  geometry::DieFillingParams dp;
  MacGrid g;
  g.nx = args.nx, g.ny = args.ny, g.nz = args.nz;
  g.dx = (dp.domain_hi.x - dp.domain_lo.x) / g.nx;
  g.origin = dp.domain_lo;
  for (int d = 0; d < 3; ++d)
    if (std::fabs(g.n()[d] * g.dx - (dp.domain_hi[d] - dp.domain_lo[d])) > 1e-9)
      throw Error("bench fluid: the grid must have cubic cells on the 84 x 42 x 30 mm domain (e.g. 140x70x50, 70x35x25)");
  geometry::Scene scene;
  geometry::add_die_filling(scene, dp);

  FluidParams fp;
  fp.rho = 1.0;
  fp.mu = 1.8e-5;
  fp.gravity = {0, 0, -9.81};
  fp.bc = uniform_boundary(BcType::Wall);
  fp.bc[5].type = BcType::Open;
  fp.pressure.method = args.method;
  fp.pressure.rel_tol = args.tolerance;
  fp.pressure.max_iter = 1000;
  fp.time_order = args.time_order;
  if (args.stage_tolerance >= 0) fp.stage_rel_tol = args.stage_tolerance;
  const double dt = 1e-4, t0 = 0.10;
  fp.dt_max = dt;

  Stopwatch sw_setup;
  FluidSolver solver(g, fp);
  FluidState s = make_fluid_state(g);
  s.t = t0;
  vortex(g, 0.1, s);
  auto shift = [&](double t) { return scene.at(t).offset[1].x; };  // body 1 = shoe
  const double v_shoe = scene.at(t0).velocity[1].x;
  bed_eps(g, dp, shift(t0), s.eps);
  const double setup_s = sw_setup.seconds();
  std::printf("fluid bench: grid %dx%dx%d (%ld cells), dx = %.3g mm, %d threads, dt = %g s, t0 = %g s, "
              "time_order %d, pressure %s tol %g (stage 1: %g)\n",
              g.nx, g.ny, g.nz, g.cells(), g.dx * 1e3, args.threads, dt, t0, fp.time_order, args.method.c_str(),
              args.tolerance, fp.stage_rel_tol > 0 ? fp.stage_rel_tol : args.tolerance);
  std::printf("state: packed bed eps = %.2f (d_O = %g um) in the die and the shoe cavity, shoe at %.3g m/s, "
              "set-up %.2f s\n", kEpsBed, kDo * 1e6, v_shoe, setup_s);

  Sources src;
  Field eps_prev;
  int iters = 0, stage_iters = 0;
  double max_div = 0, max_div_walls = 0, step_min = std::numeric_limits<double>::infinity(), step_sum = 0;
  double cpu_sum = 0, cpu_min = std::numeric_limits<double>::infinity();
  long sampled = 0;
  const int total = args.warmup + args.steps;
  for (int n = 0; n < total; ++n) {
    if (n == args.warmup) solver.timers().reset();
    const double t1 = s.t + dt;
    eps_prev = s.eps;
    s.eps_old = s.eps;                     // the caller's part of a coupled step: eps^{n+1}, K
    bed_eps(g, dp, shift(t1), s.eps);
    drag_sources(g, dp, shift(t1), v_shoe, s.eps, src);
    Stopwatch sw;
    const double cpu0 = process_cpu_seconds();
    const StepStats st = solver.advance(s, scene.at(t1), src, dt);
    const double sec = sw.seconds(), cpu = process_cpu_seconds() - cpu0;
    if (!st.pressure_converged) std::printf("warning: step %d: pressure not converged (resid %.2e)\n", n, st.pressure_residual);
    if (n < args.warmup) continue;
    if (n == total - 1) {
      const DivSplit ds = divergence_split(s, eps_prev, solver.ibm().alpha_cell, dt);
      std::printf("last step: max |div| in cells with fluid %.2e 1/s (cell %d %d %d, alpha %.3f), inside walls %.2e 1/s\n",
                  ds.fluid, ds.at[0], ds.at[1], ds.at[2], solver.ibm().alpha_cell(ds.at[0], ds.at[1], ds.at[2]),
                  ds.solid);
    }
    step_min = std::min(step_min, sec);
    step_sum += sec;
    cpu_sum += cpu;
    cpu_min = std::min(cpu_min, cpu);
    iters += st.pressure_iterations;
    stage_iters += st.stage_iterations;
    max_div = std::max(max_div, st.max_divergence);
    max_div_walls = std::max(max_div_walls, st.max_divergence_walls);
    sampled += solver.ibm().sampled_faces;
    if (!st.ibm_updated) std::printf("warning: step %d did not update the IBM fractions\n", n);
  }
  const double per_step = step_sum / args.steps;
  std::printf("%d timed steps after %d warm-up steps: pressure iterations per step %.1f (stage 1: %.1f), "
              "max |div| %.2e 1/s in cells with air (%.2e inside walls), boxes sub-sampled per step %ld\n",
              args.steps, args.warmup, double(iters) / args.steps, double(stage_iters) / args.steps, max_div,
              max_div_walls, sampled / args.steps);
  std::printf("faces inside walls that the explicit terms pass over: u %ld, v %ld, w %ld of %ld each\n",
              solver.faces_in_walls(0), solver.faces_in_walls(1), solver.faces_in_walls(2), g.cells());
  const PhaseTimers& tm = solver.timers();
  std::printf("per-phase time of one step (mean over the timed steps)\n  %-24s %10s %7s\n", "phase", "s/step", "%");
  const char* phases[] = {"checks", "ibm", "ghosts, face eps", "advection+viscous", "predictor update",
                          "pressure coefficients", "pressure set-up", "pressure rhs", "pressure solve", "correction",
                          "diagnostics"};
  double sum = 0;
  for (const char* ph : phases) sum += tm.seconds(ph);
  for (const char* ph : phases)
    std::printf("  %-24s %10.4f %6.1f%%\n", ph, tm.seconds(ph) / args.steps, 100 * tm.seconds(ph) / sum);
  std::printf("  %-24s %10.4f (outside the phases: %.4f)\n", "sum of phases", sum / args.steps,
              per_step - sum / args.steps);
  // Order-fixed sums of the final state: identical across thread counts and optimisations
  // that keep the arithmetic.
  double cs[4] = {0, 0, 0, 0};
  for (int d = 0; d < 3; ++d) {
    const Field& f = s.vel(d);
    for (int k = 0; k < f.nk(); ++k)
      for (int j = 0; j < f.nj(); ++j)
        for (int i = 0; i < f.ni(); ++i) cs[d] += std::fabs(f(i, j, k));
  }
  for (int k = 0; k < g.nz; ++k)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) cs[3] += std::fabs(s.p(i, j, k));
  std::printf("state checksum: sum|u| %.17g sum|v| %.17g sum|w| %.17g sum|p| %.17g\n", cs[0], cs[1], cs[2], cs[3]);
  std::printf("step seconds: mean %.4f, best %.4f\n", per_step, step_min);
  // Processor time of the process (all threads) per step: on a machine shared with other jobs
  // this is close to the wall time of a quiet machine with one thread (with two, it includes
  // the time threads wait at barriers).
  std::printf("step processor seconds (all threads): mean %.4f, best %.4f\n", cpu_sum / args.steps, cpu_min);
  std::printf("fluid-step-s: %.4f\n", per_step);
  return 0;
}

}  // namespace cgdem::bench
