#include "study/shuffle.h"

namespace hapcine::study {

uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

uint64_t ParticipantSeed(uint64_t plan_seed, int participant_number) {
  return SplitMix64(plan_seed ^ SplitMix64(static_cast<uint64_t>(participant_number)));
}

uint64_t StudyRng::Below(uint64_t n) {
  if (n <= 1) return 0;
  // Largest multiple of n that fits: draws at or above it are rejected.
  const uint64_t limit = UINT64_MAX - (UINT64_MAX % n);
  uint64_t r;
  do {
    r = engine_();
  } while (r >= limit);
  return r % n;
}

}  // namespace hapcine::study
