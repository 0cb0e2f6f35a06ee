// Energy and momentum budgets per unit solid mass, compared across coarse-grain ratios.
//
// From a run's energy.csv (app/energy_csv.hpp), rows from the analysis start t0 on (the
// process after any settling; cumulative terms count from t0), with M = the solid mass at
// t0 (the total: parcels that leave keep their books; eq. 4 gives the same M for every l):
//   e_trans = E_kin_trans / M, e_rot = E_kin_rot / M (the parcels' own 1/2 I w^2),
//   e_rot_orig = E_kin_rot_orig / M (the l^3 originals: e_rot / l^2 by eq. 5),
//   e_pot = (E_pot(t) - E_pot(t0)) / M, e_damp, e_fric = dissipated since t0 / M,
//   w_walls, w_air = work done on the solid since t0 / M, v_x,y,z = p / M (centre-of-mass velocity),
//   closure = (E_balance(t) - E_balance(t0)) / M          [J/kg, m/s]
// A parcel rolling without slip has w = 2 v / d = 2 v / (l d_O), so e_rot = v^2/5 holds for
// every l (it is the quantity that should agree) while e_rot_orig = v^2 / (5 l^2) falls as
// 1/l^2 (the quantity that cannot).
//
// Agreement with the reference (l = 1) run on its time base, for quantity q of run l:
//   D_q = max_t |q_l(t) - q_1(t)| / S_q
// with S_q = the energy scale S_E for energies and the closure, S_E = max_t max(|e_pot,1|,
// e_trans,1 + e_rot,1, |w_walls,1|, |w_air,1|) (the largest energy exchanged per unit mass
// in the reference run), the velocity scale sqrt(2 S_E) for momentum, and for the two
// rotational energies their own peak in the reference run (they are 1e-2..1e-3 of S_E and
// would pass on S_E whatever they did). The closure is judged per run against zero.
#pragma once
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "scaling/series.hpp"

namespace cgdem::scaling {

// Quantity names in report order.
const std::vector<std::string>& budget_quantities();
std::string budget_unit(const std::string& q);       // "J/kg" or "m/s"
std::string budget_scale_kind(const std::string& q);  // "energy", "velocity", "own peak"
std::string budget_threshold(const std::string& q);   // its threshold's name (thresholds.hpp)

struct Budget {
  std::string label;
  double ratio = 1;  // l of the run's parcels (for the E_kin_rot_orig fallback)
  double mass = 0;   // kg, M
  long particles = 0;  // parcels at the first row
  std::vector<double> t;
  std::map<std::string, std::vector<double>> q;  // budget_quantities() -> series
  bool rot_orig_derived = false;  // energy.csv had no E_kin_rot_orig: e_rot / l^2 used
};

// Reads DIR/energy.csv from t0 on. Throws cgdem::Error naming the file on a missing column,
// no row at or after t0, or M <= 0.
Budget read_budget(const std::string& energy_csv, const std::string& label, double ratio, double t0 = -INFINITY);

struct BudgetScales {
  double energy = 0;    // S_E, J/kg
  double velocity = 0;  // sqrt(2 S_E), m/s
  std::map<std::string, double> own_peak;  // max_t |q_1| per quantity
  double of(const std::string& q) const;   // S_q
};
BudgetScales budget_scales(const Budget& ref);

// A run's series on the common time base, with its deviation from the reference.
struct BudgetComparison {
  std::string label;
  std::vector<double> t;                             // common time base
  std::map<std::string, std::vector<double>> value;  // q_l on t
  std::map<std::string, std::vector<double>> dev;    // (q_l - q_1) / S_q on t
  std::map<std::string, double> max_dev, t_max_dev;  // D_q and where
  std::map<std::string, double> mean_ratio;          // time mean of q_l / q_1 where |q_1| > 5 % of its peak
};

// Every run against runs[ref] on the common time base (runs[ref] included, deviation 0).
std::vector<BudgetComparison> compare_budgets(const std::vector<Budget>& runs, size_t ref, const BudgetScales& s);

}  // namespace cgdem::scaling
