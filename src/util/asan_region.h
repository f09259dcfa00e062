/* Range-checked kernels under the sanitizers.
 *
 * ASan and UBSan check every load of an instrumented loop (addressable; not null, aligned, no
 * pointer wrap) and so keep it from being vectorised; in the nearest-neighbour kernels (short sums
 * over rows of d doubles, ~30 % of a match) that made a match under the sanitizers ~3.5x slower
 * than the release build. A kernel marked SSI_RANGE_CHECKED is compiled without those per-load
 * checks and instead calls ssi_checked_doubles / ssi_checked_ints on every array it touches, once
 * per call: the same detection (a null or misaligned start is reported by UBSan, a range that
 * reaches into a redzone or freed memory by ASan, each with the stack), one shadow scan per row
 * instead of a check per element. Every other sanitizer check (signed overflow, bounds of fixed
 * arrays, ...) stays. Outside ASan builds all of it is nothing. */
#ifndef SS_UTIL_ASAN_REGION_H
#define SS_UTIL_ASAN_REGION_H

#include <stddef.h>
#include <stdint.h>

#if defined(__SANITIZE_ADDRESS__)
#define SSI_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SSI_ASAN 1
#endif
#endif

#ifdef SSI_ASAN
#include <sanitizer/asan_interface.h>
#define SSI_RANGE_CHECKED __attribute__((no_sanitize("address", "alignment", "null", "object-size", "pointer-overflow")))
/* bytes from p must be addressable, p not null and aligned to its type (elem bytes); otherwise an
 * instrumented read (noinline: never folded into an unchecked kernel) makes the sanitizers report it
 * as they report any bad access: of the first element (null, misaligned), of the first bad byte */
__attribute__((noinline, unused)) static void ssi_checked_range(const void *p, size_t elem, size_t n) {
  if (n == 0) return;
  if (!p || (uintptr_t)p % elem) {
    if (elem == sizeof(double)) (void)*(const volatile double *)p;
    else (void)*(const volatile int *)p;
  }
  const volatile char *bad = (const volatile char *)__asan_region_is_poisoned((void *)(uintptr_t)p, elem * n);
  if (bad) (void)*bad;
}
#define ssi_checked_doubles(p, n) ssi_checked_range((p), sizeof(double), (size_t)(n))
#define ssi_checked_ints(p, n) ssi_checked_range((p), sizeof(int), (size_t)(n))
#define ssi_checked_object(p) ssi_checked_range((p), 1, sizeof *(p))
#else
#define SSI_RANGE_CHECKED
#define ssi_checked_doubles(p, n) ((void)0)
#define ssi_checked_ints(p, n) ((void)0)
#define ssi_checked_object(p) ((void)0)
#endif

#endif
