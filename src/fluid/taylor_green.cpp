#include "fluid/taylor_green.hpp"

#include <algorithm>

namespace cgdem::fluid {

namespace {

// Visits the n^2 distinct x- and y-faces of the periodic slab (face n is the image of 0):
// fn(component d, face centre x, value).
template <class Fn>
void for_each_face(const FluidState& s, Fn&& fn) {
  const auto& g = s.grid;
  for (int d = 0; d < 2; ++d)
    for (int j = 0; j < g.ny; ++j)
      for (int i = 0; i < g.nx; ++i) fn(d, g.face_centre(d, i, j, 0), s.vel(d)(i, j, 0));
}

}  // namespace

void set_taylor_green(FluidState& s, const TaylorGreen& tg, double F) {
  for (int d = 0; d < 2; ++d) {
    Field& f = s.vel(d);
    for (int kk = 0; kk < f.nk(); ++kk)
      for (int j = 0; j < f.nj(); ++j)
        for (int i = 0; i < f.ni(); ++i) {
          const Vec3 x = s.grid.face_centre(d, i, j, kk);
          f(i, j, kk) = d == 0 ? tg.u(x, F) : tg.v(x, F);
        }
  }
}

TaylorGreenErrors taylor_green_errors(const FluidState& s, const TaylorGreen& tg, double rho, double F) {
  double e2 = 0, emax = 0, ke2 = 0, proj = 0, norm1 = 0;
  for_each_face(s, [&](int d, const Vec3& x, double value) {
    const double shape = d == 0 ? tg.u(x, 1.0) : tg.v(x, 1.0), e = value - shape * F;
    e2 += e * e;
    emax = std::max(emax, std::fabs(e));
    ke2 += value * value;
    proj += value * shape;
    norm1 += shape * shape;
  });
  const int n = s.grid.nx;
  const double faces = 2.0 * n * n, cells = static_cast<double>(n) * n;
  TaylorGreenErrors r;
  r.l2 = std::sqrt(e2 / faces);
  r.max = emax;
  r.kinetic_energy = 0.5 * rho * ke2 / cells;
  r.decay_factor = proj / norm1;  // shape carries U0 already: the factor is dimensionless
  return r;
}

}  // namespace cgdem::fluid
