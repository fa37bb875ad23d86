#include "texture/value_noise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "texture/image_ops.hpp"

namespace forensim {

namespace {

// Sampling positions of eqs. 3.2 / 3.3 along one axis for coordinate p, and the blend value (p - s1) / period.
struct Taps4 {
  int s[4];
  double blend;
};

Taps4 axis_taps(int p, long long period, int size) {
  Taps4 t{};
  const long long s1 = (p / period) * period;
  const long long s0 = s1 < period ? ((size - period + s1) % size + size) % size : s1 - period;
  const long long s2 = (s1 + period) % size;
  const long long s3 = (s2 + period) % size;
  t.s[0] = static_cast<int>(s0);
  t.s[1] = static_cast<int>(s1);
  t.s[2] = static_cast<int>(s2);
  t.s[3] = static_cast<int>(s3);
  t.blend = static_cast<double>(p - s1) / static_cast<double>(period);
  return t;
}

// The lattice an octave of period P reads for coordinates [p0, p0 + n) of an axis of `size` texels: the taps of
// eqs. 3.2 and 3.3 at p are the lattice positions s1 - P, s1, s1 + P, s1 + 2P (s1 = floor(p / P) P) taken
// modulo size, so they are consecutive slots of one run: slot k holds position s1(p0) + (k - 1) P, and tap j
// of p is slot (s1(p) - s1(p0)) / P + j.
struct AxisLattice {
  std::vector<int> coords;  // per slot, the texel coordinate (modulo size)
  std::vector<int> first;   // per output coordinate, the slot of its tap 0
  std::vector<double> blend;
};

void axis_lattice(int p0, int n, long long period, int size, AxisLattice& l) {
  const long long s_first = (p0 / period) * period;
  const long long s_last = ((p0 + n - 1) / period) * period;
  const std::size_t slots = static_cast<std::size_t>((s_last - s_first) / period + 4);
  l.coords.resize(slots);
  for (std::size_t k = 0; k < slots; ++k) {
    const long long pos = s_first + (static_cast<long long>(k) - 1) * period;
    l.coords[k] = static_cast<int>(((pos % size) + size) % size);
  }
  l.first.resize(static_cast<std::size_t>(n));
  l.blend.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Taps4 t = axis_taps(p0 + i, period, size);
    l.first[static_cast<std::size_t>(i)] = static_cast<int>((t.s[1] - s_first) / period);
    l.blend[static_cast<std::size_t>(i)] = t.blend;
  }
}

}  // namespace

namespace {

// Eqs. 3.6 and 3.7, inlined into the noise loops (noise_bias and noise_gain call these).
inline double bias_of(double v, double b) {
  v = std::clamp(v, 0.0, 1.0);
  b = std::clamp(b, 0.0, 1.0);
  // v / ((1/b - 2)(1 - v) + 1), multiplied through by b so that b = 0 is defined.
  const double denominator = (1.0 - 2.0 * b) * (1.0 - v) + b;
  if (denominator <= 0.0) return v >= 1.0 ? 1.0 : 0.0;
  return v * b / denominator;
}

inline double gain_of(double v, double g) {
  v = std::clamp(v, 0.0, 1.0);
  if (v < 0.5) return bias_of(v * 2.0, g) / 2.0;
  return bias_of(v * 2.0 - 1.0, 1.0 - g) / 2.0 + 0.5;
}

}  // namespace

double noise_bias(double v, double b) {
  return bias_of(v, b);
}

double noise_gain(double v, double g) {
  return gain_of(v, g);
}

Image value_noise_base(int width, int height, std::uint64_t seed) {
  Image base(width, height, 1, 0.0f, PixelEncoding::data);
  parallel_for(
      0, static_cast<std::size_t>(height),
      [&](std::size_t y) {
        for (int x = 0; x < width; ++x)
          base.at(x, static_cast<int>(y)) = static_cast<float>(hash_uniform(
              seed, static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(width) + static_cast<std::uint64_t>(x)));
      },
      16);
  return base;
}

Image value_noise(const Image& base, const ValueNoiseParams& params) {
  const std::string source = "value noise parameters";
  require_input(base.channels() == 1 || base.empty(), "value noise base array", "",
                "needs one channel, has " + std::to_string(base.channels()));
  require_input(params.octaves >= 1 && params.octaves <= 30, source, "octaves",
                "must be in 1..30, is " + std::to_string(params.octaves));
  require_input(params.first_octave >= 0 && params.first_octave + params.octaves <= 31, source, "first_octave",
                "first_octave + octaves must be in 1..31");
  require_input(std::isfinite(params.persistence) && params.persistence > 0.0, source, "persistence",
                "must be a finite positive number");
  require_input(params.bias >= 0.0 && params.bias <= 1.0, source, "bias", "must be in [0, 1]");
  require_input(params.gain >= 0.0 && params.gain <= 1.0, source, "gain", "must be in [0, 1]");
  const int width = base.width(), height = base.height();
  Image result(width, height, 1, 0.0f, PixelEncoding::data);
  if (base.empty()) return result;

  // Amplitudes in loop order (largest period first), lines 4 to 8.
  std::vector<double> amplitude(static_cast<std::size_t>(params.octaves));
  double a = 1.0, total_amplitude = 0.0;
  for (int k = 0; k < params.octaves; ++k) {
    a *= params.persistence;
    amplitude[static_cast<std::size_t>(k)] = a;
    total_amplitude += a;
  }
  require_input(std::isfinite(total_amplitude) && total_amplitude > 0.0, source, "persistence",
                "gives a non-finite or zero total amplitude");

  const float* values = base.data().data();
  const std::size_t w = static_cast<std::size_t>(width);
  // Per octave, the horizontal cubics of lines 15 to 18 depend only on (base row, x): compute them once
  // for the base rows the octave uses, then each texel needs one vertical cubic (line 19). Same arithmetic
  // in the same order as the algorithm as printed, so the same values.
  std::vector<double> sum(w * static_cast<std::size_t>(height), 0.0);
  std::vector<Taps4> x_taps(w), y_taps(static_cast<std::size_t>(height));
  std::vector<double> horizontal;
  std::vector<std::uint8_t> row_used(static_cast<std::size_t>(height));
  for (int k = 0; k < params.octaves; ++k) {
    const int octave = params.first_octave + params.octaves - 1 - k;  // line 9: octaves downto 0
    const long long period = 1LL << octave;                           // line 10
    for (int x = 0; x < width; ++x) x_taps[static_cast<std::size_t>(x)] = axis_taps(x, period, width);  // line 14
    std::fill(row_used.begin(), row_used.end(), std::uint8_t{0});
    for (int y = 0; y < height; ++y) {
      const Taps4 ty = axis_taps(y, period, height);  // line 13
      y_taps[static_cast<std::size_t>(y)] = ty;
      for (int j = 0; j < 4; ++j) row_used[static_cast<std::size_t>(ty.s[j])] = 1;
    }
    horizontal.assign(w * static_cast<std::size_t>(height), 0.0);
    parallel_for(
        0, static_cast<std::size_t>(height),
        [&](std::size_t row) {
          if (!row_used[row]) return;
          const float* line = values + row * w;
          double* out = horizontal.data() + row * w;
          for (std::size_t x = 0; x < w; ++x) {
            const Taps4& tx = x_taps[x];
            out[x] = cubic_interpolate(line[tx.s[0]], line[tx.s[1]], line[tx.s[2]], line[tx.s[3]], tx.blend);
          }
        },
        4);
    const double amplitude_k = amplitude[static_cast<std::size_t>(k)];
    parallel_for(
        0, static_cast<std::size_t>(height),
        [&](std::size_t row) {
          const Taps4& ty = y_taps[row];
          const double* r0 = horizontal.data() + static_cast<std::size_t>(ty.s[0]) * w;
          const double* r1 = horizontal.data() + static_cast<std::size_t>(ty.s[1]) * w;
          const double* r2 = horizontal.data() + static_cast<std::size_t>(ty.s[2]) * w;
          const double* r3 = horizontal.data() + static_cast<std::size_t>(ty.s[3]) * w;
          double* acc = sum.data() + row * w;
          for (std::size_t x = 0; x < w; ++x)
            acc[x] += cubic_interpolate(r0[x], r1[x], r2[x], r3[x], ty.blend) * amplitude_k;  // line 19
        },
        4);
  }
  parallel_for(
      0, static_cast<std::size_t>(height),
      [&](std::size_t row) {
        for (std::size_t x = 0; x < w; ++x) {  // lines 20 to 22
          const double v = std::clamp(sum[row * w + x] / total_amplitude, 0.0, 1.0);
          result.at(static_cast<int>(x), static_cast<int>(row)) =
              static_cast<float>(gain_of(bias_of(v, params.bias), params.gain));
        }
      },
      4);
  return result;
}

Image value_noise(int width, int height, const ValueNoiseParams& params) {
  return value_noise(value_noise_base(width, height, params.seed), params);
}

}  // namespace forensim

namespace forensim {

ValueNoiseField::ValueNoiseField(int width, int height, const ValueNoiseParams& params)
    : m_width(width), m_height(height), m_params(params) {
  const std::string source = "value noise parameters";
  require_input(width > 0 && height > 0, "value noise field", "size", "must be positive");
  require_input(params.octaves >= 1 && params.octaves <= 30, source, "octaves",
                "must be in 1..30, is " + std::to_string(params.octaves));
  require_input(params.first_octave >= 0 && params.first_octave + params.octaves <= 31, source, "first_octave",
                "first_octave + octaves must be in 1..31");
  require_input(std::isfinite(params.persistence) && params.persistence > 0.0, source, "persistence",
                "must be a finite positive number");
  require_input(params.bias >= 0.0 && params.bias <= 1.0, source, "bias", "must be in [0, 1]");
  require_input(params.gain >= 0.0 && params.gain <= 1.0, source, "gain", "must be in [0, 1]");
  double a = 1.0;
  for (int k = 0; k < params.octaves; ++k) {
    a *= params.persistence;
    m_amplitude.push_back(a);
    m_total_amplitude += a;
  }
  require_input(std::isfinite(m_total_amplitude) && m_total_amplitude > 0.0, source, "persistence",
                "gives a non-finite or zero total amplitude");
}

namespace {

// Eq. 3.4 in float, as a shader computes it.
inline float cubic_f(float v0, float v1, float v2, float v3, float t) {
  const float p = (v3 - v2) - (v0 - v1);
  const float q = (v0 - v1) - p;
  const float r = v2 - v0;
  return ((p * t + q) * t + r) * t + v1;
}

// Eqs. 3.6 and 3.7 in float without branches (so the loop over a row vectorises); v and b in [0, 1].
inline float bias_f(float v, float b) {
  const float d = (1.0f - 2.0f * b) * (1.0f - v) + b;
  const float r = v * b / (d > 0.0f ? d : 1.0f);
  return d > 0.0f ? r : (v >= 1.0f ? 1.0f : 0.0f);
}

inline float gain_f(float v, float g) {
  const bool low = v < 0.5f;
  const float r = bias_f(low ? 2.0f * v : 2.0f * v - 1.0f, low ? g : 1.0f - g);
  return 0.5f * r + (low ? 0.0f : 0.5f);
}

}  // namespace

void ValueNoiseField::evaluate(int x0, int y0, int w, int h, float* out, std::size_t stride) const {
  const int xa = std::max(x0, 0), ya = std::max(y0, 0);
  const int xb = std::min(x0 + w, m_width), yb = std::min(y0 + h, m_height);
  if (xb <= xa || yb <= ya) return;
  out += static_cast<std::size_t>(ya - y0) * stride + static_cast<std::size_t>(xa - x0);
  x0 = xa;
  y0 = ya;
  w = xb - xa;
  h = yb - ya;
  const std::size_t sw = static_cast<std::size_t>(w);
  struct Scratch {
    std::vector<float> sum, horizontal, cache, lattice, blend_x;
    std::vector<std::size_t> runs;
    AxisLattice cols, rows;
  };
  thread_local Scratch s;
  s.sum.assign(sw * static_cast<std::size_t>(h), 0.0f);
  // Base values of the rectangle itself, hashed on first read (-1: not yet).
  s.cache.assign(sw * static_cast<std::size_t>(h), -1.0f);
  const std::uint64_t seed = m_params.seed;
  const std::uint64_t W = static_cast<std::uint64_t>(m_width);
  auto base = [&](int x, int y) {
    const auto value = [&] {
      return static_cast<float>(hash_uniform(seed, static_cast<std::uint64_t>(y) * W + static_cast<std::uint64_t>(x)));
    };
    if (x < x0 || x >= x0 + w || y < y0 || y >= y0 + h) return value();
    float& c = s.cache[static_cast<std::size_t>(y - y0) * sw + static_cast<std::size_t>(x - x0)];
    if (c < 0.0f) c = value();
    return c;
  };
  s.blend_x.resize(sw);
  for (int k = 0; k < m_params.octaves; ++k) {
    const int octave = m_params.first_octave + m_params.octaves - 1 - k;
    const long long period = 1LL << octave;
    axis_lattice(x0, w, period, m_width, s.cols);
    axis_lattice(y0, h, period, m_height, s.rows);
    const std::size_t nc = s.cols.coords.size(), nr = s.rows.coords.size();
    s.lattice.resize(nc * nr);
    for (std::size_t r = 0; r < nr; ++r)
      for (std::size_t c = 0; c < nc; ++c) s.lattice[r * nc + c] = base(s.cols.coords[c], s.rows.coords[r]);
    // Horizontal cubics of lines 15 to 18 on the lattice rows, one lattice cell (a run of x sharing their
    // four taps) at a time so the loop over its texels vectorises.
    s.runs.clear();
    for (std::size_t x = 0; x < sw; ++x) {
      if (s.runs.empty() || s.cols.first[x] != s.cols.first[s.runs.back()]) s.runs.push_back(x);
      s.blend_x[x] = static_cast<float>(s.cols.blend[x]);
    }
    s.runs.push_back(sw);
    s.horizontal.resize(nr * sw);
    for (std::size_t r = 0; r < nr; ++r) {
      const float* line = s.lattice.data() + r * nc;
      float* hout = s.horizontal.data() + r * sw;
      if (period == 1) {  // blend 0: the lattice values themselves
        for (std::size_t x = 0; x < sw; ++x) hout[x] = line[s.cols.first[x] + 1];
        continue;
      }
      for (std::size_t run = 0; run + 1 < s.runs.size(); ++run) {
        const std::size_t begin = s.runs[run], end = s.runs[run + 1];
        const float* v = line + s.cols.first[begin];
        const float v0 = v[0], v1 = v[1], v2 = v[2], v3 = v[3];
        for (std::size_t x = begin; x < end; ++x) hout[x] = cubic_f(v0, v1, v2, v3, s.blend_x[x]);
      }
    }
    // Line 19.
    const float amplitude_k = static_cast<float>(m_amplitude[static_cast<std::size_t>(k)]);
    for (int y = 0; y < h; ++y) {
      const float t = static_cast<float>(s.rows.blend[static_cast<std::size_t>(y)]);
      const float* r0 = s.horizontal.data() + static_cast<std::size_t>(s.rows.first[static_cast<std::size_t>(y)]) * sw;
      const float* r1 = r0 + sw;
      const float* r2 = r1 + sw;
      const float* r3 = r2 + sw;
      float* acc = s.sum.data() + static_cast<std::size_t>(y) * sw;
      if (t == 0.0f) {
        for (std::size_t x = 0; x < sw; ++x) acc[x] += r1[x] * amplitude_k;
      } else {
        for (std::size_t x = 0; x < sw; ++x) acc[x] += cubic_f(r0[x], r1[x], r2[x], r3[x], t) * amplitude_k;
      }
    }
  }
  // Lines 20 to 22.
  const float inverse_total = static_cast<float>(1.0 / m_total_amplitude);
  const float b = static_cast<float>(m_params.bias), g = static_cast<float>(m_params.gain);
  if (b > 0.0f && b < 1.0f && g > 0.0f && g < 1.0f) {
    // Every denominator of eqs. 3.6 and 3.7 is then positive: no special cases, so the loop vectorises.
    const float gh = 1.0f - g;
    for (int y = 0; y < h; ++y) {
      const float* acc = s.sum.data() + static_cast<std::size_t>(y) * sw;
      float* o = out + static_cast<std::size_t>(y) * stride;
      std::size_t x = 0;
#if defined(__SSE2__)
      // Four texels at a time (the same operations as the loop below, so the same values).
      const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.0f), two = _mm_set1_ps(2.0f), half = _mm_set1_ps(0.5f),
                   inv = _mm_set1_ps(inverse_total), vb = _mm_set1_ps(b), vb2 = _mm_set1_ps(1.0f - 2.0f * b),
                   vg = _mm_set1_ps(g), vg2 = _mm_set1_ps(1.0f - 2.0f * g), vgh = _mm_set1_ps(gh),
                   vgh2 = _mm_set1_ps(1.0f - 2.0f * gh);
      for (; x + 4 <= sw; x += 4) {
        const __m128 v = _mm_min_ps(_mm_max_ps(_mm_mul_ps(_mm_loadu_ps(acc + x), inv), zero), one);
        const __m128 bv = _mm_div_ps(_mm_mul_ps(v, vb), _mm_add_ps(_mm_mul_ps(vb2, _mm_sub_ps(one, v)), vb));
        const __m128 lo = _mm_mul_ps(two, bv), hi = _mm_sub_ps(_mm_mul_ps(two, bv), one);
        const __m128 r_lo = _mm_div_ps(_mm_mul_ps(lo, vg), _mm_add_ps(_mm_mul_ps(vg2, _mm_sub_ps(one, lo)), vg));
        const __m128 r_hi = _mm_div_ps(_mm_mul_ps(hi, vgh), _mm_add_ps(_mm_mul_ps(vgh2, _mm_sub_ps(one, hi)), vgh));
        const __m128 is_low = _mm_cmplt_ps(bv, half);
        const __m128 a = _mm_mul_ps(half, r_lo), c = _mm_add_ps(_mm_mul_ps(half, r_hi), half);
        _mm_storeu_ps(o + x, _mm_or_ps(_mm_and_ps(is_low, a), _mm_andnot_ps(is_low, c)));
      }
#endif
      for (; x < sw; ++x) {
        const float v = std::min(std::max(acc[x] * inverse_total, 0.0f), 1.0f);
        const float bv = v * b / ((1.0f - 2.0f * b) * (1.0f - v) + b);
        const float lo = 2.0f * bv, hi = 2.0f * bv - 1.0f;
        const float r_lo = lo * g / ((1.0f - 2.0f * g) * (1.0f - lo) + g);
        const float r_hi = hi * gh / ((1.0f - 2.0f * gh) * (1.0f - hi) + gh);
        o[x] = bv < 0.5f ? 0.5f * r_lo : 0.5f * r_hi + 0.5f;
      }
    }
    return;
  }
  for (int y = 0; y < h; ++y) {
    const float* acc = s.sum.data() + static_cast<std::size_t>(y) * sw;
    float* o = out + static_cast<std::size_t>(y) * stride;
    for (std::size_t x = 0; x < sw; ++x) {
      const float v = std::min(std::max(acc[x] * inverse_total, 0.0f), 1.0f);
      o[x] = gain_f(bias_f(v, b), g);
    }
  }
}

}  // namespace forensim
