#include "solvers/run/domain.hpp"

namespace cgdem::run {

AirShare SerialDomain::share_air(const AirSpec& air) {
  AirShare s;
  s.grid = air.grid;
  s.fluid = air.fluid;
  s.exchange = air.exchange;
  s.pressure_text = "pressure " + air.fluid.pressure.method;
  return s;
}

}  // namespace cgdem::run
