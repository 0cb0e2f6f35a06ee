// Energy bookkeeping of the contact law over many collisions. Three spinning parcels
// (l = 2) bounce on a floor and on each other with damping and friction for 30 ms; the
// budget E_kin + E_pot + E_el + dissipated stays at its initial value to within 1 % of the
// potential energy released at the paper's step (1e-6 s) at all times, and the largest
// closure error falls by more than 2 when dt falls by 4: what is left is the time
// discretization of the contact events (a contact starts and ends between two steps,
// which makes the error's sign depend on the phase), not the bookkeeping.
#include <gtest/gtest.h>

#include "dem_test_util.hpp"

namespace cgdem {
namespace {

double closure_error(double dt) {
  MaterialParams m;
  m.restitution = m.wall_restitution = 0.7;
  m.friction = m.wall_friction = 0.3;
  return test::closure_error(dt, m);
}

TEST(Budget, ClosureErrorIsSmallAndShrinksWithDt) {
  const double e1 = closure_error(1e-6), e2 = closure_error(0.5e-6), e4 = closure_error(0.25e-6);
  std::printf("[ budget ] largest closure error / energy released: dt=1e-6 %.2e, 5e-7 %.2e, 2.5e-7 %.2e "
              "(tol: 1e-2 at 1e-6; dt/4 at least 2x smaller: %.1fx)\n",
              e1, e2, e4, e1 / e4);
  EXPECT_LT(e1, 1e-2);
  EXPECT_LT(e2, 1e-2);
  EXPECT_GT(e1 / e4, 2.0);
}

}  // namespace
}  // namespace cgdem
