// c ? a : b without a branch: both operands are evaluated and the result is a blend of
// their bits under a mask of c, so it is exactly a or b. A loop written with it needs no
// if-conversion to vectorize; written as ?:, GCC may make a branch of it, move each side's
// floating-point work into its branch and then not take it out again (an FP operation may
// trap), and the loop does not vectorize. Used by the contact laws and the air's advection.
#pragma once
#include <bit>
#include <cstdint>

#include "core/vec3.hpp"

namespace cgdem {

inline double select(bool c, double a, double b) {
  const uint64_t m = -static_cast<uint64_t>(c);
  return std::bit_cast<double>((std::bit_cast<uint64_t>(a) & m) | (std::bit_cast<uint64_t>(b) & ~m));
}
inline Vec3 select(bool c, const Vec3& a, const Vec3& b) {
  return {select(c, a.x, b.x), select(c, a.y, b.y), select(c, a.z, b.z)};
}

}  // namespace cgdem
