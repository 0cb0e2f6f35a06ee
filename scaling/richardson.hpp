// Richardson extrapolation, observed order and grid convergence index (GCI) of a quantity
// f computed at several values of a discretisation parameter h (cell size, time step).
//
// Levels are sorted fine to coarse, h_1 < h_2 < h_3. For one triple (Roache 1998, ch. 5;
// Celik et al. 2008, J. Fluids Eng. 130, 078001, eqs. 1-7), with
//   e21 = f2 - f1,  e32 = f3 - f2,  r21 = h2/h1 > 1,  r32 = h3/h2 > 1,
// the model f(h) = f0 + C h^p (asymptotic range) gives
//   e32/e21 = g(p),  g(p) = r21^p (r32^p - 1) / (r21^p - 1)                        (1)
// (Celik eq. 3-4 with s = +1). For a constant ratio r21 = r32 = r this is
//   p = ln(e32/e21) / ln r.                                                       (2)
// For a non-constant ratio (1) is nonlinear in p. g is continuous and strictly increasing
// on p > 0 (d ln g/dp = ln r32 r32^p/(r32^p - 1) - ln r21/(r21^p - 1) >= 1/p - 1/p, since
// y ln y >= y - 1 and x^p - 1 >= p ln x), from g(0+) = ln r32 / ln r21 to infinity, so
// (1) has exactly one root p > 0 when e32/e21 > g(0+), found here by bisection (no
// starting guess, cannot diverge, unlike the fixed-point form of Celik eq. 4).
//
// Behaviour of the triple (reported instead of a meaningless p):
//   monotone     e32/e21 > g(0+): p > 0 from (1)
//   oscillatory  e32/e21 < 0: the differences change sign
//   divergent    0 < e32/e21 <= g(0+): the differences do not shrink with h (p <= 0)
//   flat         |e21| at round-off (rel_roundoff * max|f|): p cannot be determined
//                (also when the root of (1) exceeds kMaxOrder)
//
// For a monotone triple:
//   f_ext   = f1 + (f1 - f2) / (r21^p - 1)                      (Richardson; Celik eq. 5)
//   GCI_21  = Fs |f1 - f2| / (r21^p - 1)   (absolute, units of f; Roache, Celik eq. 7)
// with the safety factor Fs = 1.25 (Roache's value for three or more grids with an
// observed order). The relative GCI is GCI_21/|f1|. (Roache's asymptotic-range check
// GCI_32 / (r21^p GCI_21) = 1 is an identity when p comes from the same triple, so it is
// not reported; with more levels, compare the orders of consecutive triples instead.) For an oscillatory triple the
// uncertainty reported is the spread max f - min f of the three values.
//
// More than three levels: one result per consecutive triple. When the exact value f* is
// known, a least-squares fit of ln|f_i - f*| = ln C + p ln h_i over all levels gives one
// order for the whole sequence.
#pragma once
#include <string>
#include <vector>

namespace cgdem::scaling {

inline constexpr double kGciSafetyFactor = 1.25;  // Fs, Roache (three or more levels)
inline constexpr double kMaxOrder = 64.0;          // roots of (1) above this: "flat"
inline constexpr double kRelRoundoff = 1e-12;      // differences below this x max|f|: zero

struct Level {
  double h = 0;  // discretisation parameter (> 0)
  double f = 0;  // the quantity at that h
};

enum class Behaviour { Monotone, Oscillatory, Divergent, Flat };
std::string to_string(Behaviour b);

struct TripleResult {
  Level fine, medium, coarse;     // h ascending
  double r21 = 0, r32 = 0;        // refinement ratios h2/h1, h3/h2
  Behaviour behaviour = Behaviour::Flat;
  double order = 0;               // p (NaN unless monotone)
  double extrapolated = 0;        // f_ext (NaN unless monotone)
  double gci_fine = 0;            // GCI_21, absolute (NaN unless monotone)
  double gci_fine_rel = 0;        // GCI_21 / |f1| (NaN unless monotone and f1 != 0)
  double spread = 0;              // max f - min f of the three values
};

// p from (1) for e32/e21 = ratio; NaN when there is no root p in (0, kMaxOrder].
// Preconditions: r21 > 1, r32 > 1.
double observed_order(double ratio, double r21, double r32);

// The analysis of one triple (any order of the three levels; they are sorted by h).
// Throws cgdem::Error when two levels share an h, an h is not positive and finite, or an
// f is not finite (the same for the functions below).
TripleResult analyse_triple(Level a, Level b, Level c, double rel_roundoff = kRelRoundoff);

// One result per consecutive triple of the levels sorted by h (empty for fewer than 3).
std::vector<TripleResult> analyse_sequence(std::vector<Level> levels, double rel_roundoff = kRelRoundoff);

// Least-squares fit of ln|f_i - exact| = ln C + p ln h_i.
struct PowerFit {
  double order = 0;      // p (NaN if fewer than 2 levels with a non-zero error)
  double constant = 0;   // C
  double max_log_residual = 0;  // max_i |ln|e_i| - ln C - p ln h_i| (0: an exact power law)
  int levels = 0;        // levels used (those with e_i != 0)
  int sign_changes = 0;  // sign changes of f_i - exact along h (non-zero: not one power law)
};
PowerFit fit_error_power_law(std::vector<Level> levels, double exact);

}  // namespace cgdem::scaling
