#pragma once
/// Value noise exactly as the wound thesis specifies it (K. Linnenbank, "Real-time simulation of abrasion wound
/// healing", MSc thesis, Utrecht University 2015; chapter 3.3.2, Algorithm 3.2): one seeded
/// base array of uniform [0, 1) values the size of the texture; each octave i samples it on a lattice of
/// period 2^i texels with the bicubic of eq. 3.4 (sampling positions of eqs. 3.2 and 3.3, wrapping around
/// the texture edges), weighted by an amplitude multiplied by the persistence before every octave (largest
/// period first, eq. 3.5); the sum is divided by the total amplitude, then shaped by bias (eq. 3.6) and gain
/// (eq. 3.7).
///
/// Scale: periods are in texels, so the thesis's parameters give its look at its texture scale. To keep the
/// same look at a resolution k times finer, raise `first_octave` by log2(k) (periods 2^(first_octave + i)).
/// The result tiles seamlessly (it is a function on the torus) when width and height are multiples of the
/// largest period; otherwise it is still defined and wraps, with a crease at the right and bottom edges.

#include <cstdint>
#include <vector>

#include "image/image.hpp"

namespace forensim {

/// Bias of eq. 3.6 (Schlick's bias): v / ((1/b - 2)(1 - v) + 1), bending [0, 1] up (b > 0.5) or down
/// (b < 0.5); bias(v, 0.5) = v, bias(0, b) = 0, bias(1, b) = 1. The thesis's printed eq. 3.6 lacks the
/// "- 2", but its text (0.5 leaves the noise unchanged) needs it. v and b are clamped to [0, 1]; b = 0 gives
/// 0 below v = 1.
double noise_bias(double v, double b);

/// Gain of eq. 3.7 as printed: bias(2v, g) / 2 for v < 0.5, else bias(2v - 1, 1 - g) / 2 + 0.5 (contrast);
/// gain(v, 0.5) = v, gain(0, g) = 0, gain(0.5, g) = 0.5, gain(1, g) = 1. This equals Perlin's gain with
/// 1 - g, so g < 0.5 steepens the midrange and g > 0.5 flattens it (the thesis's prose says the opposite,
/// but its parameters, e.g. gain 0.02 for a near-binary mask, fit the equation, which is kept).
double noise_gain(double v, double g);

/// Parameters of Algorithm 3.2.
struct ValueNoiseParams {
  int octaves = 5;  ///< number of octaves, 1..30; the thesis's "octaves downto 0" loop read as octaves - 1 downto 0
  double persistence = 0.5;  ///< amplitude factor per octave, > 0 (the thesis uses 0.09 to 1.0)
  double bias = 0.5;         ///< eq. 3.6, in [0, 1]; 0.5 = unchanged
  double gain = 0.5;         ///< eq. 3.7, in [0, 1]; 0.5 = unchanged
  int first_octave = 0;      ///< periods are 2^(first_octave + i), i = octaves - 1 down to 0
  std::uint64_t seed = 1;    ///< seed of the base array
};

/// The seeded base array (Algorithm 3.2, lines 2 and 3): width x height single-channel data image of
/// uniform [0, 1) values, value(x, y) = hash_uniform(seed, y * width + x), so independent of threads.
Image value_noise_base(int width, int height, std::uint64_t seed);

/// Algorithm 3.2 on a given base array (single channel; its size is the output size): a width x height
/// single-channel data image with values in [0, 1] (the octave sum is clamped to [0, 1] before bias and
/// gain, as a shader's saturate; the cubic of eq. 3.4 may overshoot). Rows are computed in parallel; the
/// result does not depend on the thread count. Throws InputError for bad parameters.
Image value_noise(const Image& base, const ValueNoiseParams& params);

/// Algorithm 3.2 from start to end: value_noise(value_noise_base(width, height, params.seed), params).
Image value_noise(int width, int height, const ValueNoiseParams& params);

/// Algorithm 3.2 for a width x height noise evaluated on any rectangle of it, without building the base
/// array: a lattice value is hashed where it is read (the same hash_uniform(seed, y * width + x) as
/// value_noise_base). Same steps as value_noise in 32-bit float, as the thesis's shaders compute them
/// (value_noise works in double; the two agree within 1e-5). For maps that read noise only in some tiles (a
/// wound's noise layers are read inside the wound only): the cost is that of the texels evaluated, not of
/// the texture. Set up once (parameter checks, amplitudes), then evaluate() from any number of threads; a
/// texel's value does not depend on the rectangle it is evaluated in.
class ValueNoiseField {
 public:
  /// Throws InputError for bad parameters (as value_noise) or a non-positive size.
  ValueNoiseField(int width, int height, const ValueNoiseParams& params);
  int width() const { return m_width; }
  int height() const { return m_height; }
  /// Noise at texels [x0, x0 + w) x [y0, y0 + h) (clipped to the field) into out[(y - y0) * stride + x - x0].
  /// Serial; thread-safe (scratch memory is per thread).
  void evaluate(int x0, int y0, int w, int h, float* out, std::size_t stride) const;

 private:
  int m_width = 0, m_height = 0;
  ValueNoiseParams m_params;
  std::vector<double> m_amplitude;  // per loop step, largest period first
  double m_total_amplitude = 0.0;
};

}  // namespace forensim
