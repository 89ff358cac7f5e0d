// Deterministic random numbers (doc/algorithms.md §7): pcg32 streams seeded through SplitMix64
// from a path such as (seed, item, object, purpose), and our own uniform and normal transforms
// (the std:: distributions differ between standard libraries, so they are never used).
#pragma once

#include <cstdint>
#include <initializer_list>

#include <glm/vec3.hpp>
#include <pcg_random.hpp>

namespace cutaway {

/// One step of SplitMix64 (Steele, Lea, Flood 2014): advances `state` by the golden gamma and
/// returns the mixed value. Used to derive seeds; never as the generator itself.
uint64_t splitmix64(uint64_t& state);

/// A 64-bit seed for one purpose: SplitMix64 over `seed` and then every element of `path`
/// (e.g. {item, object, purpose}). Different paths give unrelated seeds; the same path always
/// gives the same seed on every platform.
uint64_t derive_seed(uint64_t seed, std::initializer_list<uint64_t> path);

/// A pcg32 stream (O'Neill 2014) with platform-independent transforms. State and stream
/// selector both come from SplitMix64 of the seed, so nearby seeds give unrelated streams.
class Rng {
 public:
  /// @param seed usually derive_seed(...) of the caller's path
  explicit Rng(uint64_t seed);

  /// The next raw 32-bit output of pcg32.
  uint32_t next_u32() { return gen_(); }

  /// Uniform in [0, 1) with 53 random bits (two pcg32 outputs: 27 + 26 bits), so every double
  /// k * 2^-53 is equally likely.
  double uniform();

  /// Uniform in [a, b) (a + (b - a) * uniform()).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }

  /// Standard normal N(0, 1) by the Marsaglia polar method (pairs; the second value of a pair
  /// is kept for the next call). Uses std::sqrt and std::log (IEEE-754 sqrt is exact; glibc's
  /// log is correctly rounded in practice, so results agree across x86-64 and AArch64 glibc).
  double normal();

  /// Uniform integer in [0, n), unbiased (rejection of the short last interval).
  /// @pre n > 0
  uint32_t below(uint32_t n);

 private:
  pcg32 gen_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

/// A direction uniform on the unit sphere: a point uniform in the cube [-1, 1)^3, drawn again
/// until it lies in the unit ball (and not within 1e-3 of its centre), then normalised.
glm::dvec3 random_direction(Rng& rng);

}  // namespace cutaway
