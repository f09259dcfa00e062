/* splitmix64 (Steele, Lea, Flood 2014): tiny, fast and the same stream everywhere, so pairs and
 * landmarks depend on the seed only — never on the C library's rand(). */
#include "specseg/eval.h"

void ss_rng_seed(ss_rng *r, uint64_t seed) { r->state = seed; }

uint64_t ss_rng_next(ss_rng *r) {
  uint64_t z = (r->state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

int ss_rng_below(ss_rng *r, int n) {
  if (n <= 1) return 0;
  /* reject the top partial block so every value is equally likely */
  uint64_t un = (uint64_t)n, limit = UINT64_MAX - UINT64_MAX % un;
  uint64_t v;
  do v = ss_rng_next(r);
  while (v >= limit);
  return (int)(v % un);
}
