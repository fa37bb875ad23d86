#pragma once
/// Seeded random streams whose values depend only on (seed, stream id, draw number), never on thread
/// count or scheduling: give each independent work item (a texel row, a particle, an ensemble member) its
/// own stream id and results are identical at any thread count.

#include <cstdint>

namespace forensim {

/// SplitMix64 finaliser: a bijective 64-bit mix with good avalanche (Steele et al. 2014).
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

/// Counter-based stream: the n-th draw is a hash of (seed, stream, n).
class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t stream) : m_key(mix64(seed ^ mix64(stream + 0x632BE59BD9B4E019ull))) {}

  /// Next raw 64-bit value.
  std::uint64_t next_u64() { return mix64(m_key + mix64(m_counter++)); }
  /// Uniform double in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  /// Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [lo, hi] (inclusive); requires lo <= hi.
  std::int64_t uniform_int(std::int64_t lo, std::int64_t hi);
  /// Standard normal draw (Box-Muller, one value per call).
  double normal();
  /// Normal draw with the given mean and standard deviation.
  double normal(double mean, double sd) { return mean + sd * normal(); }
  /// Number of draws made so far (for checkpoints).
  std::uint64_t counter() const { return m_counter; }
  void set_counter(std::uint64_t counter) { m_counter = counter; }

 private:
  std::uint64_t m_key;
  std::uint64_t m_counter = 0;
};

/// Stateless uniform [0,1) value for (seed, a, b): lattice noise and per-texel jitter.
inline double hash_uniform(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
  return static_cast<double>(mix64(mix64(seed ^ mix64(a)) + b) >> 11) * 0x1.0p-53;
}

}  // namespace forensim
