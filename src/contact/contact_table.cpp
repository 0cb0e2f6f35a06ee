// The square root of contact_law.hpp and its vector variants, defined under other C++
// names (bound to the ABI's symbols) before the header's `declare simd` declaration, so
// that the compiler does not make its own clones of them.
#include <immintrin.h>

#include <cmath>

extern "C" {
double cgdem_sqrt_scalar(double x) __asm__("cgdem_sqrt");
double cgdem_sqrt_scalar(double x) { return std::sqrt(x); }
__m128d cgdem_sqrt_sse(__m128d x) __asm__("_ZGVbN2v_cgdem_sqrt");
__m128d cgdem_sqrt_sse(__m128d x) { return _mm_sqrt_pd(x); }
__attribute__((target("avx"))) __m256d cgdem_sqrt_avx(__m256d x) __asm__("_ZGVcN4v_cgdem_sqrt");
__attribute__((target("avx"))) __m256d cgdem_sqrt_avx(__m256d x) { return _mm256_sqrt_pd(x); }
__attribute__((target("avx2"))) __m256d cgdem_sqrt_avx2(__m256d x) __asm__("_ZGVdN4v_cgdem_sqrt");
__attribute__((target("avx2"))) __m256d cgdem_sqrt_avx2(__m256d x) { return _mm256_sqrt_pd(x); }
__attribute__((target("avx512f"))) __m512d cgdem_sqrt_avx512(__m512d x) __asm__("_ZGVeN8v_cgdem_sqrt");
__attribute__((target("avx512f"))) __m512d cgdem_sqrt_avx512(__m512d x) { return _mm512_mask_sqrt_pd(x, 0xFF, x); }
}

#include "contact/contact_table.hpp"

#include <algorithm>

namespace cgdem {

namespace {
double pair_m_eff(const Species& a, const Species& b) {
  double ma = a.original_mass(), mb = b.original_mass();
  return ma * mb / (ma + mb);
}
}  // namespace

ContactTable::ContactTable(const std::vector<Species>& species, const MaterialParams& m)
    : n_(static_cast<int>(species.size())), m_(m), species_(species) {
  pair_.resize(n_ * n_);
  wall_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    for (int j = 0; j < n_; ++j) {
      double l = std::min(species[i].ratio, species[j].ratio);
      pair_[i * n_ + j] = {m.stiffness,
                           contact::damping_coefficient(m.restitution, pair_m_eff(species[i], species[j]), m.stiffness),
                           m.friction, l * l * l};
    }
    wall_[i] = {m.stiffness,
                contact::damping_coefficient(m.wall_restitution, species[i].original_mass(), m.stiffness),
                m.wall_friction, species[i].l3()};
  }
}

double ContactTable::pair_collision_time(int si, int sj) const {
  return contact::contact_time(m_.restitution, pair_m_eff(species_[si], species_[sj]), m_.stiffness);
}

double ContactTable::wall_collision_time(int s) const {
  return contact::contact_time(m_.wall_restitution, species_[s].original_mass(), m_.stiffness);
}

double ContactTable::min_collision_time() const {
  double t = INFINITY;
  for (int i = 0; i < n_; ++i) {
    t = std::min(t, wall_collision_time(i));
    for (int j = 0; j < n_; ++j) t = std::min(t, pair_collision_time(i, j));
  }
  return t;
}

}  // namespace cgdem
