/* Exits 0 when this processor and its operating system run x86-64-v3 code:
 * the feature list of the x86-64 psABI's micro-architecture levels (v2:
 * CMPXCHG16B, LAHF/SAHF, POPCNT, SSE3, SSSE3, SSE4.1, SSE4.2; v3 adds AVX,
 * AVX2, BMI1, BMI2, F16C, FMA, LZCNT, MOVBE, OSXSAVE), read from CPUID bits
 * as Intel's Software Developer's Manual, vol. 2A (CPUID), numbers them.
 * CPUID directly, not __builtin_cpu_supports("x86-64-v3"): Clang 14 rejects
 * that name and several single features, and CMake then quietly built the
 * portable baseline. */
#include <cpuid.h>

int main(void) {
  unsigned a, b, c1, d, b7, c7, e1;
  if (!__get_cpuid(1, &a, &b, &c1, &d)) return 1;
  if (!__get_cpuid_count(7, 0, &a, &b7, &c7, &d)) return 1;
  if (!__get_cpuid(0x80000001u, &a, &b, &e1, &d)) return 1;
  /* leaf 1, ECX: SSE3 0, SSSE3 9, FMA 12, CMPXCHG16B 13, SSE4.1 19,
   * SSE4.2 20, MOVBE 22, POPCNT 23, OSXSAVE 27, AVX 28, F16C 29 */
  const unsigned need1 = (1u << 0) | (1u << 9) | (1u << 12) | (1u << 13) | (1u << 19) | (1u << 20) |
                         (1u << 22) | (1u << 23) | (1u << 27) | (1u << 28) | (1u << 29);
  /* leaf 7, EBX: BMI1 3, AVX2 5, BMI2 8 */
  const unsigned need7 = (1u << 3) | (1u << 5) | (1u << 8);
  /* leaf 0x80000001, ECX: LAHF/SAHF 0, LZCNT 5 */
  const unsigned need_e = (1u << 0) | (1u << 5);
  if ((c1 & need1) != need1 || (b7 & need7) != need7 || (e1 & need_e) != need_e) return 1;
  /* The operating system saves the SSE and AVX registers (XCR0 bits 1, 2). */
  unsigned lo, hi;
  __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
  (void)hi;
  return (lo & 6u) == 6u ? 0 : 1;
}
