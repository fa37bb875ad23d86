#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "texture/image_ops.hpp"
#include "texture/value_noise.hpp"

using namespace forensim;

namespace {

// Algorithm 3.2 written out plainly (serial, every index computed as eqs. 3.2 and 3.3 print it), as the
// reference for the parallel implementation.
Image reference_value_noise(const Image& base, int octaves, double persistence, double bias, double gain) {
  const int w = base.width(), h = base.height();
  std::vector<double> t(static_cast<std::size_t>(w * h), 0.0);
  double amplitude = 1.0, total = 0.0;
  for (int oct = octaves - 1; oct >= 0; --oct) {
    amplitude *= persistence;
    total += amplitude;
    const int period = 1 << oct;
    const double frequency = 1.0 / period;
    for (int py = 0; py < h; ++py) {
      const int y1 = py / period * period;
      const int y0 = y1 < period ? h - period + y1 : y1 - period;
      const int y2 = (y1 + period) % h, y3 = (y2 + period) % h;
      const double vert = (py - y1) * frequency;
      for (int px = 0; px < w; ++px) {
        const int x1 = px / period * period;
        const int x0 = x1 < period ? w - period + x1 : x1 - period;
        const int x2 = (x1 + period) % w, x3 = (x2 + period) % w;
        const double hor = (px - x1) * frequency;
        const int ys[4] = {y0, y1, y2, y3};
        double rows[4];
        for (int j = 0; j < 4; ++j)
          rows[j] =
              cubic_interpolate(base.at(x0, ys[j]), base.at(x1, ys[j]), base.at(x2, ys[j]), base.at(x3, ys[j]), hor);
        t[static_cast<std::size_t>(py * w + px)] +=
            cubic_interpolate(rows[0], rows[1], rows[2], rows[3], vert) * amplitude;
      }
    }
  }
  Image out(w, h, 1);
  for (int i = 0; i < w * h; ++i) {
    const double v = std::clamp(t[static_cast<std::size_t>(i)] / total, 0.0, 1.0);
    out.data()[static_cast<std::size_t>(i)] = static_cast<float>(noise_gain(noise_bias(v, bias), gain));
  }
  return out;
}

}  // namespace

TEST(NoiseBiasGain, Identities) {
  for (double t = 0.0; t <= 1.0; t += 0.05) {
    EXPECT_NEAR(noise_bias(t, 0.5), t, 1e-15);  // bias(t, 0.5) = t
    EXPECT_NEAR(noise_gain(t, 0.5), t, 1e-15);  // gain(t, 0.5) = t
  }
  for (double g : {0.0, 0.02, 0.21, 0.43, 0.69, 0.95, 1.0}) {
    EXPECT_DOUBLE_EQ(noise_gain(0.0, g), 0.0);
    EXPECT_DOUBLE_EQ(noise_gain(0.5, g), 0.5);
    EXPECT_DOUBLE_EQ(noise_gain(1.0, g), 1.0);
    EXPECT_DOUBLE_EQ(noise_bias(0.0, g), 0.0);
    EXPECT_DOUBLE_EQ(noise_bias(1.0, g), 1.0);
  }
  // Schlick's bias: bias(0.5, b) = b, and bias bends up for b > 0.5, down below.
  for (double b : {0.1, 0.3, 0.7, 0.9}) EXPECT_NEAR(noise_bias(0.5, b), b, 1e-15);
  EXPECT_GT(noise_bias(0.3, 0.8), 0.3);
  EXPECT_LT(noise_bias(0.3, 0.2), 0.3);
  // Eq. 3.7 as printed is Perlin's gain with 1 - g: g below 0.5 steepens the midrange (the thesis's
  // speckles, gain 0.15, and its near-binary mask, gain 0.02), above 0.5 flattens it.
  EXPECT_GT(noise_gain(0.6, 0.2) - 0.5, 0.2);
  EXPECT_LT(noise_gain(0.6, 0.8) - 0.5, 0.05);
  for (double v = 0.0; v <= 1.0; v += 0.05)
    for (double g : {0.1, 0.3, 0.8}) {
      const double perlin = v < 0.5 ? noise_bias(2 * v, 1 - (1 - g)) / 2 : 1 - noise_bias(2 - 2 * v, 1 - (1 - g)) / 2;
      EXPECT_NEAR(noise_gain(v, g), perlin, 1e-12);
    }
  for (double v : {0.1, 0.3, 0.45}) EXPECT_NEAR(noise_gain(v, 0.3) + noise_gain(1.0 - v, 0.3), 1.0, 1e-12);
  // Monotone.
  double previous = -1.0;
  for (double t = 0.0; t <= 1.0; t += 0.01) {
    const double v = noise_gain(noise_bias(t, 0.16), 0.15);
    EXPECT_GE(v, previous);
    previous = v;
  }
}

TEST(ValueNoise, MatchesTheAlgorithmAsPrinted) {
  ValueNoiseParams params;
  params.octaves = 5;
  params.persistence = 0.48;
  params.bias = 0.16;
  params.gain = 0.15;
  params.seed = 11;
  const Image base = value_noise_base(64, 48, params.seed);
  const Image noise = value_noise(base, params);
  const Image expected = reference_value_noise(base, 5, 0.48, 0.16, 0.15);
  ASSERT_EQ(noise.width(), 64);
  ASSERT_EQ(noise.height(), 48);
  for (std::size_t i = 0; i < noise.data().size(); ++i) ASSERT_NEAR(noise.data()[i], expected.data()[i], 1e-6);
  // One octave of period 1 returns the base array (bias, gain 0.5: unchanged).
  ValueNoiseParams one;
  one.octaves = 1;
  const Image identity = value_noise(base, one);
  for (std::size_t i = 0; i < base.data().size(); ++i) ASSERT_FLOAT_EQ(identity.data()[i], base.data()[i]);
}

TEST(ValueNoise, ValuesInUnitRangeAndNotFlat) {
  ValueNoiseParams params;
  params.octaves = 5;
  params.persistence = 0.85;
  const Image noise = value_noise(64, 64, params);
  const auto [lo, hi] = std::minmax_element(noise.data().begin(), noise.data().end());
  EXPECT_GE(*lo, 0.0f);
  EXPECT_LE(*hi, 1.0f);
  EXPECT_GT(*hi - *lo, 0.3f);
}

TEST(ValueNoise, TilesAcrossTheEdges) {
  ValueNoiseParams params;
  params.octaves = 4;  // largest period 8 divides 64
  params.persistence = 0.7;
  params.seed = 5;
  const Image base = value_noise_base(64, 64, params.seed);
  const Image noise = value_noise(base, params);
  // A function on the torus: rolling the base array by a multiple of the largest period rolls the noise.
  Image rolled(64, 64, 1);
  const int sx = 24, sy = 40;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) rolled.at((x + sx) % 64, (y + sy) % 64) = base.at(x, y);
  const Image rolled_noise = value_noise(rolled, params);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) ASSERT_FLOAT_EQ(rolled_noise.at((x + sx) % 64, (y + sy) % 64), noise.at(x, y));
  // And the seam is as smooth as the inside: the step across the wrap is no larger than the largest step.
  double inner = 0.0, seam = 0.0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x + 1 < 64; ++x) inner = std::max(inner, double(std::abs(noise.at(x + 1, y) - noise.at(x, y))));
    seam = std::max(seam, double(std::abs(noise.at(0, y) - noise.at(63, y))));
  }
  EXPECT_LE(seam, 1.5 * inner);
}

TEST(ValueNoise, SameSeedSameOutputAtAnyThreadCount) {
  ValueNoiseParams params;
  params.octaves = 6;
  params.persistence = 0.54;
  params.bias = 0.3;
  params.gain = 0.69;
  params.seed = 77;
  const int previous = thread_count();
  set_thread_count(1);
  const Image one = value_noise(96, 80, params);
  set_thread_count(2);
  const Image two = value_noise(96, 80, params);
  set_thread_count(previous);
  EXPECT_EQ(one.data(), two.data());
  params.seed = 78;
  EXPECT_NE(value_noise(96, 80, params).data(), one.data());
}

TEST(ValueNoise, FirstOctaveScalesTheLook) {
  // At twice the resolution with first_octave + 1, the lattice values sit at the same relative places:
  // a base array upsampled by 2 (each value at even texels) reproduces the coarse noise at even texels.
  ValueNoiseParams coarse_params;
  coarse_params.octaves = 3;
  coarse_params.persistence = 0.6;
  const Image coarse_base = value_noise_base(32, 32, 9);
  Image fine_base(64, 64, 1);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) fine_base.at(2 * x, 2 * y) = coarse_base.at(x, y);
  ValueNoiseParams fine_params = coarse_params;
  fine_params.first_octave = 1;
  const Image coarse = value_noise(coarse_base, coarse_params);
  const Image fine = value_noise(fine_base, fine_params);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) ASSERT_NEAR(fine.at(2 * x, 2 * y), coarse.at(x, y), 1e-6);
}

TEST(ValueNoise, RejectsBadParameters) {
  ValueNoiseParams params;
  params.octaves = 0;
  EXPECT_THROW(value_noise(8, 8, params), InputError);
  params.octaves = 3;
  params.persistence = -1.0;
  EXPECT_THROW(value_noise(8, 8, params), InputError);
  params.persistence = 0.5;
  params.bias = 1.5;
  EXPECT_THROW(value_noise(8, 8, params), InputError);
  params.bias = 0.5;
  EXPECT_THROW(value_noise(Image(4, 4, 3), params), InputError);
  // Periods larger than the texture still give finite values.
  params.octaves = 8;
  const Image small = value_noise(5, 3, params);
  for (float v : small.data()) EXPECT_TRUE(std::isfinite(v));
}

TEST(ValueNoise, FieldOnRectanglesEqualsTheWholeNoise) {
  // Sizes that are not multiples of the periods (wrap-around taps) and periods larger than the noise.
  for (const auto& [w, h, octaves, first] :
       {std::tuple{70, 45, 5, 0}, std::tuple{33, 100, 7, 1}, std::tuple{64, 64, 10, 0}}) {
    ValueNoiseParams params;
    params.octaves = octaves;
    params.first_octave = first;
    params.persistence = 0.54;
    params.bias = 0.3;
    params.gain = 0.69;
    params.seed = 1234;
    const Image whole = value_noise(w, h, params);
    const ValueNoiseField field(w, h, params);
    std::vector<float> out(static_cast<std::size_t>(w * h), -1.0f);
    // Tiles of 16 x 16, clipped at the edges.
    for (int y0 = 0; y0 < h; y0 += 16)
      for (int x0 = 0; x0 < w; x0 += 16)
        field.evaluate(x0, y0, 16, 16, out.data() + static_cast<std::size_t>(y0 * w + x0), static_cast<std::size_t>(w));
    // In float (as a shader) against the double reference.
    for (std::size_t i = 0; i < out.size(); ++i)
      ASSERT_NEAR(out[i], whole.data()[i], 1e-5) << w << "x" << h << " " << i;
    // A texel's value does not depend on the rectangle it is evaluated in.
    float one = -1.0f;
    field.evaluate(w / 2, h / 3, 1, 1, &one, 1);
    EXPECT_EQ(one, out[static_cast<std::size_t>((h / 3) * w + w / 2)]);
  }
  EXPECT_THROW(ValueNoiseField(0, 4, ValueNoiseParams{}), InputError);
}
