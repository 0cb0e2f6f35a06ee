// The unit and meaning of every case key, for the generated reference (case_keys.hpp):
// one row per key that a reader asks for. Type, default and allowed values are not
// written here: they come from the readers' own calls. A key added to a reader without a
// row here (or a row whose key no reader asks for) stops `cgdem keys` with its name.
#include "app/case_keys.hpp"

namespace cgdem::app {

namespace {

// [particles]: the parcels, their species and where they come from.
std::vector<KeyDoc> particle_keys() {
  return {
    {"particles.seed", "1", "seed of the random insertion (each [[particles.insert]] takes the next one)"},
    {"particles.skin", "m",
     "neighbour-list skin; 0: a tenth of the largest parcel diameter; at most 10 largest diameters"},
    {"particles.species[].name", "", "the species' name, each once (inserts and files refer to it)"},
    {"particles.species[].d_original", "m", "diameter d_O of the original particle"},
    {"particles.species[].ratio", "1", "coarse-grain ratio l: a parcel of diameter l d_O stands for l^3 originals"},
    {"particles.species[].density", "kg/m^3", "solid density (the densest solids are about 2.3e4)"},
    {"particles.insert[].species", "", "the species inserted (a name of [[particles.species]])"},
    {"particles.insert[].min", "m", "the region's lower corner, inside the domain (not with `region`)"},
    {"particles.insert[].max", "m", "the region's upper corner, inside the domain, above `min` on every axis"},
    {"particles.insert[].count", "1",
     "parcels inserted at random without overlap (not with `solid_volume`); count x parcel volume at most 0.7405 "
     "of the region (random insertion stops near 0.3)"},
    {"particles.insert[].velocity", "m/s", "their initial velocity"},
    {"particles.insert[].region", "",
     "instead of min/max: \"die_filling_cavity\", the shoe's cavity at t = 0 (needs [walls.die_filling])"},
    {"particles.insert[].solid_volume", "m^3",
     "instead of `count`: the solid volume to insert, rounded to whole parcels (at least half a parcel, at most "
     "1e8 parcels)"},
    {"particles.file[].path", "",
     "parcels read from a file (CSV x,y,z,d or a particle snapshot .h5), relative to the case file's folder"},
    {"particles.file[].species", "", "the species of the parcels read"},
  };
}

// [contact]: the contact law and its material.
std::vector<KeyDoc> contact_keys() {
  return {
    {"contact.youngs_modulus", "Pa", "hertz-mindlin: Young's modulus of the original particles"},
    {"contact.poisson_ratio", "1", "hertz-mindlin: Poisson's ratio, in (-1, 0.5]"},
    {"contact.wall_youngs_modulus", "Pa", "hertz-mindlin: Young's modulus of the walls",
     "= `contact.youngs_modulus`"},
    {"contact.wall_poisson_ratio", "1", "hertz-mindlin: Poisson's ratio of the walls", "= `contact.poisson_ratio`"},
    {"contact.max_impact_speed", "m/s",
     "hertz-mindlin: the fastest impact the time step must resolve (the Hertz collision time falls with speed)"},
    {"contact.law", "",
     "contact law: linear (spring-dashpot, the paper's) or hertz-mindlin, whose own keys `cgdem run --help` and "
     "docs/contact_laws.md list"},
    {"contact.stiffness", "N/m", "normal spring stiffness k of the linear spring-dashpot law"},
    {"contact.restitution", "1", "coefficient of restitution between parcels"},
    {"contact.friction", "1", "Coulomb friction coefficient between parcels"},
    {"contact.wall_restitution", "1", "coefficient of restitution against walls", "= `contact.restitution`"},
    {"contact.wall_friction", "1", "Coulomb friction coefficient against walls", "= `contact.friction`"},
  };
}

// [domain], [physics]: the box, its periodic axes, gravity.
std::vector<KeyDoc> domain_keys() {
  return {
    {"domain.min", "m",
     "lower corner of the domain (every coordinate in [-1000, 1000]); parcels leaving the domain are removed and "
     "counted"},
    {"domain.max", "m",
     "upper corner, above `min`; at most 2e8 neighbour-search cells of one interaction range (largest diameter "
     "plus skin)"},
    {"domain.periodic", "",
     "periodic axes: parcels leaving on one side come back on the other; a periodic length is at least three "
     "interaction ranges"},
    {"physics.gravity", "m/s^2", "gravity, every component in [-1e5, 1e5]"},
  };
}

// [walls.die_filling]: the die-filling geometry.
std::vector<KeyDoc> die_filling_keys() {
  return {
    {"walls.die_filling.die_type", "1", "1: shallow section on the side the shoe reaches first, 2: on the far side"},
    {"walls.die_filling.domain_min", "m", "lower corner of the die-filling geometry's box"},
    {"walls.die_filling.domain_max", "m", "its upper corner"},
    {"walls.die_filling.table_top", "m",
     "height of the table top, the plane the shoe slides on (with air: best a plane of the air grid)"},
    {"walls.die_filling.mouth_x0", "m", "start of the die mouth along x (the shoe's direction)"},
    {"walls.die_filling.mouth_length", "m", "length of the die mouth along x"},
    {"walls.die_filling.mouth_y0", "m", "start of the die mouth along y"},
    {"walls.die_filling.mouth_width", "m", "width of the die mouth along y"},
    {"walls.die_filling.deep_depth", "m", "depth of the deep section below the table top"},
    {"walls.die_filling.shallow_depth", "m", "depth of the shallow section (at most `deep_depth`)"},
    {"walls.die_filling.step_fraction", "1", "share of the mouth length taken by the shallow section"},
    {"walls.die_filling.floor_thickness", "m", "thickness of the die floor (the floor lies inside the domain)"},
    {"walls.die_filling.cavity_size", "m", "inner size of the shoe's cavity (x, y, z)"},
    {"walls.die_filling.cavity_x0", "m", "the cavity's trailing inner wall along x at t = 0"},
    {"walls.die_filling.shoe_wall", "m", "thickness of the shoe's walls around the cavity"},
    {"walls.die_filling.shoe_gap", "m", "gap between the shoe and the table (0: it slides on the table)"},
    {"walls.die_filling.shoe_lid", "", "a lid closes the cavity's top"},
    {"walls.die_filling.shoe_speed", "m/s", "the shoe's speed along +x"},
    {"walls.die_filling.shoe_start", "s", "time the shoe starts to move"},
    {"walls.die_filling.shoe_ramp", "s", "time from rest to full speed"},
  };
}

// [[walls.body]], [[walls.body.part]], [walls]: moving bodies of wall primitives.
std::vector<KeyDoc> wall_keys() {
  return {
    {"walls.body[].velocity", "m/s", "constant velocity of the body (not with `times`/`velocities`)"},
    {"walls.body[].name", "", "the body's name"},
    {"walls.body[].times", "s", "instead of `velocity`: times of a velocity table, increasing"},
    {"walls.body[].velocities", "m/s", "the velocity at each of `times`, linear in between"},
    {"walls.body[].part[].name", "", "the part's name", "`\"part0\"`, `\"part1\"`, ... in order"},
    {"walls.body[].part[].type", "", "the part's shape"},
    {"walls.body[].part[].min", "m", "box: lower corner"},
    {"walls.body[].part[].max", "m", "box: upper corner, above `min` on every axis"},
    {"walls.body[].part[].inside_free", "",
     "true: the shape's inside is free and its outside solid (a container)"},
    {"walls.body[].part[].point", "m", "halfspace: a point of its plane"},
    {"walls.body[].part[].normal", "1", "halfspace: the plane's normal, pointing out of the wall (not zero)"},
    {"walls.body[].part[].p0", "m", "cylinder, cone, ring: one end of its axis"},
    {"walls.body[].part[].p1", "m", "cylinder, cone, ring: the other end (not `p0`)"},
    {"walls.body[].part[].radius", "m", "cylinder, sphere: the radius"},
    {"walls.body[].part[].radius0", "m", "cone: the radius at `p0` (0: an apex)"},
    {"walls.body[].part[].radius1", "m", "cone: the radius at `p1` (not 0 together with `radius0`)"},
    {"walls.body[].part[].radius_inner", "m", "ring: the inner radius (the hole's, or a tube's bore)"},
    {"walls.body[].part[].radius_outer", "m", "ring: the outer radius (above `radius_inner`)"},
    {"walls.body[].part[].centre", "m", "sphere: its centre"},
    {"walls.sdf_cutoff", "m", "distance within which walls are looked for, at least the largest parcel radius"},
  };
}

// [time], [output]: the run's span, step and outputs.
std::vector<KeyDoc> run_keys() {
  return {
    {"time.dt", "s",
     "DEM time step, at most the shortest collision time / `min_steps_per_collision`; at most 1e12 steps from "
     "`start` to `end`"},
    {"time.start", "s", "start time (before 0: settling before the shoe moves; the state at 0 is saved)"},
    {"time.end", "s", "end time, after `start`"},
    {"time.min_steps_per_collision", "1", "DEM steps at least per shortest collision"},
    // [output]
    {"output.dir", "", "output folder (`--output` overrides it)"},
    {"output.energy_interval", "s", "simulated time between rows of energy.csv"},
    {"output.snapshot_interval", "s", "simulated time between snapshots (particles, air)"},
    {"output.tracer_time", "s",
     "the parcels' heights at the first snapshot at or after this time are carried in every later snapshot as "
     "the tracer field z_start (where the powder came from)"},
    {"output.progress_interval", "s", "wall-clock time between progress lines when not on a terminal"},
    {"output.max_speed", "m/s", "a faster parcel or air velocity stops the run (a blow-up)"},
    {"output.checkpoint_interval", "s", "simulated time between checkpoints (checkpoint.bin)"},
    {"output.compression", "1", "deflate level of the HDF5 snapshots (0: none)"},
    {"output.energy_accounts", "",
     "false: the contact energy accounts are not kept (faster; the same motion to the last bit); energy.csv then "
     "says that its dissipation, wall-work and balance columns were not computed and holds nan in them"},
  };
}

// [air]: the air phase and its coupling to the parcels.
std::vector<KeyDoc> air_keys() {
  return {
    {"air.enabled", "", "false: the same case in vacuum"},
    {"air.dx", "m",
     "cubic cell size; the domain is a whole number (>= 2) of cells along each axis, at most 1e5 per axis and 1e8 "
     "in all"},
    {"air.density", "kg/m^3", "air density"},
    {"air.viscosity", "Pa s", "dynamic viscosity of the air"},
    {"air.cfl", "1", "advective Courant number that limits the fluid step"},
    {"air.time_order", "1", "1: forward Euler predictor, 2: Heun"},
    {"air.ibm_samples", "1", "n of the n^3 sub-samples per cell of the wall fraction"},
    {"air.dt_max", "s", "largest fluid step (also limited by the CFL and viscous limits), at least `time.dt`"},
    {"air.feedback", "", "false: one-way coupling (the air ignores the parcels)"},
    {"air.coupling", "",
     "drag coefficient frozen at the step's start (semi-implicit), or at the step's end velocity solved with the "
     "air by KINSOL (implicit; one process only)"},
    {"air.implicit.method", "", "implicit coupling: KINSOL fixed point with Anderson acceleration, or Newton-SPGMR"},
    {"air.implicit.tolerance", "m/s", "implicit coupling: largest accepted change of a face velocity"},
    {"air.implicit.max_iterations", "1", "implicit coupling: nonlinear iterations at most per fluid step"},
    {"air.implicit.depth", "1", "implicit coupling: Anderson depth (docs/coupling.md says why 1)"},
    {"air.pressure.method", "", "pressure solver (docs/pressure.md)"},
    {"air.pressure.krylov", "", "the conjugate-gradient engine: SUNDIALS PCG, or the same recurrence fused"},
    {"air.pressure.tolerance", "1", "relative residual of the pressure solves"},
    {"air.pressure.max_iterations", "1", "iterations at most per pressure solve"},
    {"air.pressure.stage_tolerance", "1", "relative residual of the Heun stage-1 solve (time_order = 2)"},
    {"air.pressure.mpi_preconditioner", "",
     "over MPI ranks only: preconditioner of the distributed solve; auto: as-mg2 on up to 4 ranks, pfmg beyond "
     "when built with hypre (docs/scale_out.md)"},
    {"air.boundary.open_pressure", "Pa", "pressure of the still air at the top plane; a lower open side adds the weight of the air above it (an open side must be normal to gravity)"},
    {"air.boundary.x_min", "", "the domain's side at x = min", "`\"wall\"` (`\"periodic\"` on a periodic axis)"},
    {"air.boundary.x_max", "", "the side at x = max", "`\"wall\"` (`\"periodic\"` on a periodic axis)"},
    {"air.boundary.y_min", "", "the side at y = min", "`\"wall\"` (`\"periodic\"` on a periodic axis)"},
    {"air.boundary.y_max", "", "the side at y = max", "`\"wall\"` (`\"periodic\"` on a periodic axis)"},
    {"air.boundary.z_min", "", "the side at z = min", "`\"wall\"` (`\"periodic\"` on a periodic axis)"},
    {"air.boundary.z_max", "", "the side at z = max", "`\"open\"` (`\"periodic\"` on a periodic axis)"},
    {"air.drag", "", "drag law, with the original particle's diameter (coupling/drag.hpp)"},
    {"air.eps_min", "1", "lower bound of the void fraction mapped from the parcels"},
    {"air.wall_porosity", "",
     "porosity of cells next to walls: packing = that of the packing the parcels form (kernel capacity of the "
     "cell), cell = 1 - V_s/dx^3 with the walls counted as void (docs/coupling.md)"},
  };
}

// [diagnostics]: the die-filling observables.
std::vector<KeyDoc> diagnostics_keys() {
  return {
    {"diagnostics.interval", "s",
     "time between rows of diagnostics.csv, rounded up to a multiple of at least the largest step"},
    {"diagnostics.rate_window", "s", "window of the backward difference of the transfer rate"},
    {"diagnostics.impact_band", "m",
     "height above the die floor within which a parcel has reached it (0: a quarter of the largest parcel "
     "diameter)"},
    {"diagnostics.impact_window", "s", "window after the first impact over which the impact velocity is averaged"},
    {"diagnostics.eps_bubble", "1", "void fraction from which a cell counts as air in the bubble census"},
    {"diagnostics.surface_interval", "s", "time between profiles of shoe_surface.csv"},
    {"diagnostics.surface_bins", "1", "bins over the cavity's length in shoe_surface.csv"},
    {"diagnostics.pressure_cell[].name", "",
     "a box whose cells' gauge pressure diagnostics.csv averages (default: A, B, C in the die)"},
    {"diagnostics.pressure_cell[].min", "m", "its lower corner"},
    {"diagnostics.pressure_cell[].max", "m", "its upper corner, above `min` on every axis"},
  };
}

// [flow]: the single-phase flow cases.
std::vector<KeyDoc> flow_keys() {
  return {
    {"flow.kind", "", "the flow: the periodic 2-D Taylor-Green vortex"},
    {"flow.n", "1", "cells per side"},
    {"flow.length", "m", "side L of the periodic box", "`6.28319` (2 pi)"},
    {"flow.amplitude", "m/s", "velocity amplitude U0"},
    {"flow.end", "s", "end time"},
    {"flow.density", "kg/m^3", "density"},
    {"flow.viscosity", "Pa s", "dynamic viscosity"},
    {"flow.time_order", "1", "1: forward Euler, 2: Heun"},
    {"flow.advection", "", "advection scheme"},
    {"flow.pressure.method", "", "pressure solver"},
    {"flow.pressure.tolerance", "1", "relative residual of every pressure solve"},
    {"flow.pressure.max_iterations", "1", "iterations at most per pressure solve"},
    {"flow.dt", "s",
     "fixed step (not with `cfl`); `end` is a whole number of steps, at most 1e9, within the explicit limit"},
    {"flow.cfl", "1", "instead of `dt`: a fraction of the explicit limit, dt = end / ceil(end / (cfl dt_lim))"},
  };
}

}  // namespace

const std::vector<KeyDoc>& case_key_docs() {
  static const std::vector<KeyDoc> docs = [] {
    std::vector<KeyDoc> all;
    for (auto part : {particle_keys, contact_keys, domain_keys, die_filling_keys, wall_keys, run_keys, air_keys,
                      diagnostics_keys, flow_keys})
      for (KeyDoc& d : part()) all.push_back(std::move(d));
    return all;
  }();
  return docs;
}

}  // namespace cgdem::app
