#include "image/colormap.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "image/color.hpp"

namespace forensim {
namespace {

using Poly = std::array<std::array<double, 3>, 7>;

// Coefficients c0..c6 of the polynomial fits (Matt Zucker, "matplotlib colormaps as polynomials", 2017).
constexpr Poly viridis_poly = {{{0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
                                {0.1050930431085774, 1.404613529898575, 1.384590162594685},
                                {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
                                {-4.634230498983486, -5.799100973351585, -19.33244095627987},
                                {6.228269936347081, 14.17993336680509, 56.69055260068105},
                                {4.776384997670288, -13.74514537774601, -65.35303263337234},
                                {-5.435455855934631, 4.645852612178535, 26.3124352495832}}};
constexpr Poly inferno_poly = {{{0.0002189403691192265, 0.001651004631001012, -0.01948089843709184},
                                {0.1065134194856116, 0.5639564367884091, 3.932712388889277},
                                {11.60249308247187, -3.972853965665698, -15.9423941062914},
                                {-41.70399613139459, 17.43639888205313, 44.35414519872813},
                                {77.162935699427, -33.40235894210092, -81.80730925738993},
                                {-71.31942824499214, 32.62606426397723, 73.20951985803202},
                                {25.13112622477341, -12.24266895238567, -23.07032500287172}}};
constexpr Poly magma_poly = {{{-0.002136485053939582, -0.000749655052795221, -0.005386127855323933},
                              {0.2516605407371642, 0.6775232436837668, 2.494026599312351},
                              {8.353717279216625, -3.577719514958484, 0.3144679030132573},
                              {-27.66873308576866, 14.26473078096533, -13.64921318813922},
                              {52.17613981234068, -27.94360607168351, 12.94416944238394},
                              {-50.76852536473588, 29.04658282127291, 4.23415299384598},
                              {18.65570506591883, -11.48977351997711, -5.601961508734096}}};

Vec3f evaluate(const Poly& p, double t) {
  Vec3f out;
  for (int c = 0; c < 3; ++c) {
    double v = p[6][static_cast<std::size_t>(c)];
    for (int k = 5; k >= 0; --k) v = v * t + p[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)];
    out[c] = static_cast<float>(std::clamp(v, 0.0, 1.0));
  }
  return out;
}

// Turbo, polynomial approximation by Anton Mikhailov (Google AI blog, 2019).
Vec3f turbo(double x) {
  const double x2 = x * x, x3 = x2 * x, x4 = x2 * x2, x5 = x4 * x;
  const double r =
      0.13572138 + 4.61539260 * x - 42.66032258 * x2 + 132.13108234 * x3 - 152.94239396 * x4 + 59.28637943 * x5;
  const double g = 0.09140261 + 2.19418839 * x + 4.84296658 * x2 - 14.18503333 * x3 + 4.27729857 * x4 + 2.82956604 * x5;
  const double b =
      0.10667330 + 12.64194608 * x - 60.58204836 * x2 + 110.36276771 * x3 - 89.90310912 * x4 + 27.34824973 * x5;
  return {static_cast<float>(std::clamp(r, 0.0, 1.0)), static_cast<float>(std::clamp(g, 0.0, 1.0)),
          static_cast<float>(std::clamp(b, 0.0, 1.0))};
}

// Moreland's cool-warm map (sRGB control points at t = 0, 0.25, 0.5, 0.75, 1), interpolated in linear
// light so the midpoint stays a neutral light grey.
Vec3f blue_white_red(double t) {
  static const float points[5][3] = {{0.230f, 0.299f, 0.754f},
                                     {0.552f, 0.690f, 0.996f},
                                     {0.867f, 0.867f, 0.867f},
                                     {0.958f, 0.604f, 0.482f},
                                     {0.706f, 0.016f, 0.150f}};
  const double s = t * 4.0;
  const int i = std::min(3, static_cast<int>(std::floor(s)));
  const float f = static_cast<float>(s - i);
  Vec3f out;
  for (int c = 0; c < 3; ++c) {
    const float a = srgb_to_linear(points[i][c]), b = srgb_to_linear(points[i + 1][c]);
    out[c] = linear_to_srgb(a + (b - a) * f);
  }
  return out;
}

}  // namespace

Colormap Colormap::from_name(const std::string& name, const std::string& source) {
  const std::vector<std::string> names = colormap_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return Colormap(static_cast<ColormapName>(i));
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InputError(source, "", "unknown colormap '" + name + "' (known: " + known + ")");
}

Vec3f Colormap::sample_srgb(double t) const {
  if (!std::isfinite(t)) t = 0.0;
  t = std::clamp(t, 0.0, 1.0);
  switch (m_name) {
    case ColormapName::viridis:
      return evaluate(viridis_poly, t);
    case ColormapName::inferno:
      return evaluate(inferno_poly, t);
    case ColormapName::magma:
      return evaluate(magma_poly, t);
    case ColormapName::turbo:
      return turbo(t);
    case ColormapName::blue_white_red:
      return blue_white_red(t);
    case ColormapName::grey:
      break;
  }
  const float v = static_cast<float>(t);
  return {v, v, v};
}

Vec3f Colormap::sample(double t) const {
  const Vec3f s = sample_srgb(t);
  return {srgb_to_linear(s[0]), srgb_to_linear(s[1]), srgb_to_linear(s[2])};
}

Vec3f Colormap::map(double value, double lo, double hi) const {
  const double range = hi - lo;
  return sample(range != 0.0 ? (value - lo) / range : 0.5);
}

Image colorize(const Image& values, const Colormap& map, double lo, double hi, const Vec3f& nan_colour) {
  Image out(values.width(), values.height(), 3, 0.0f, PixelEncoding::srgb);
  const double range = hi - lo;
  for (int y = 0; y < values.height(); ++y)
    for (int x = 0; x < values.width(); ++x) {
      const double v = values.at(x, y, 0);
      const Vec3f c = std::isnan(v) ? nan_colour : map.sample_srgb(range != 0.0 ? (v - lo) / range : 0.5);
      float* p = out.pixel(x, y);
      p[0] = c[0];
      p[1] = c[1];
      p[2] = c[2];
    }
  return out;
}

std::vector<std::string> colormap_names() {
  return {"viridis", "inferno", "magma", "turbo", "blue_white_red", "grey"};
}

std::string to_string(ColormapName name) {
  return colormap_names()[static_cast<std::size_t>(name)];
}

}  // namespace forensim
