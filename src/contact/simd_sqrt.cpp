// The square root of contact/history.hpp (cgdem_sqrt) and its vector variants, defined
// under other C++ names (bound to the ABI's symbols) before the header's `declare simd`
// declaration, so that the compiler does not make its own clones of them.
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
