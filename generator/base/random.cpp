#include "base/random.h"

#include <cmath>

#include <glm/geometric.hpp>

#include "base/error.h"

namespace cutaway {

uint64_t splitmix64(uint64_t& state) {
  uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

uint64_t derive_seed(uint64_t seed, std::initializer_list<uint64_t> path) {
  uint64_t state = seed;
  uint64_t h = splitmix64(state);
  for (uint64_t p : path) {
    // Mix the element into the state, then draw: (seed, a, b) and (seed, b, a) differ.
    state = h ^ (p * 0xd1342543de82ef95ULL + 0x2545f4914f6cdd1dULL);
    h = splitmix64(state);
  }
  return h;
}

namespace {

pcg32 make_pcg(uint64_t seed) {
  uint64_t s = seed;
  const uint64_t state = splitmix64(s);
  const uint64_t stream = splitmix64(s);
  return pcg32(state, stream);
}

}  // namespace

Rng::Rng(uint64_t seed) : gen_(make_pcg(seed)) {}

double Rng::uniform() {
  const uint64_t a = gen_() >> 5;  // 27 bits
  const uint64_t b = gen_() >> 6;  // 26 bits
  return static_cast<double>((a << 26) | b) * 0x1.0p-53;
}

double Rng::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u, v, s;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * f;
  has_spare_ = true;
  return u * f;
}

uint32_t Rng::below(uint32_t n) {
  CUTAWAY_CHECK(n > 0);
  const uint32_t threshold = static_cast<uint32_t>(-n) % n;  // 2^32 mod n
  for (;;) {
    const uint32_t r = gen_();
    if (r >= threshold) return r % n;
  }
}

glm::dvec3 random_direction(Rng& rng) {
  while (true) {
    const glm::dvec3 d(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
    const double len = glm::length(d);
    if (len > 1e-3 && len <= 1) return d / len;
  }
}

}  // namespace cutaway
