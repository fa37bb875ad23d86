#include "image/color.hpp"

#include <algorithm>
#include <cmath>

namespace forensim {
namespace {

Image convert(const Image& in, PixelEncoding target, float (*curve)(float)) {
  Image out = in;
  out.set_encoding(target);
  const int colour_channels = (in.channels() == 2 || in.channels() == 4) ? in.channels() - 1 : in.channels();
  std::vector<float>& d = out.data();
  const std::size_t n = static_cast<std::size_t>(in.channels());
  for (std::size_t i = 0; i < d.size(); i += n)
    for (int c = 0; c < colour_channels; ++c)
      d[i + static_cast<std::size_t>(c)] = curve(d[i + static_cast<std::size_t>(c)]);
  return out;
}

}  // namespace

float srgb_to_linear(float encoded) {
  const float v = std::clamp(encoded, 0.0f, 1.0f);
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float linear) {
  if (!(linear > 0.0f)) return 0.0f;  // also maps NaN to 0
  if (linear >= 1.0f) return 1.0f;
  const float v = linear;
  return v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

Image to_srgb(const Image& linear) {
  if (linear.encoding() != PixelEncoding::linear) return linear;
  return convert(linear, PixelEncoding::srgb, &linear_to_srgb);
}

Image to_linear(const Image& srgb) {
  if (srgb.encoding() != PixelEncoding::srgb) return srgb;
  return convert(srgb, PixelEncoding::linear, &srgb_to_linear);
}

}  // namespace forensim
