#include "texture/normal_from_height.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {

Image normal_from_height(const Image& height_mm, double texels_per_mm, double strength) {
  if (!(texels_per_mm > 0.0) || !std::isfinite(texels_per_mm) || !std::isfinite(strength)) {
    throw InputError("normal_from_height", "texels_per_mm", "must be finite and positive");
  }
  const int w = height_mm.width();
  const int h = height_mm.height();
  Image out(w, h, 3, 0.0f, PixelEncoding::data);
  if (height_mm.empty()) return out;
  const float scale = static_cast<float>(0.5 * texels_per_mm * strength);
  parallel_for(
      0, static_cast<std::size_t>(h),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        const int ym = std::max(y - 1, 0);
        const int yp = std::min(y + 1, h - 1);
        for (int x = 0; x < w; ++x) {
          const int xm = std::max(x - 1, 0);
          const int xp = std::min(x + 1, w - 1);
          const float du = (height_mm.at(xp, y) - height_mm.at(xm, y)) * scale;
          const float dv = (height_mm.at(x, ym) - height_mm.at(x, yp)) * scale;
          const float inv = 1.0f / std::sqrt(du * du + dv * dv + 1.0f);
          float* p = out.pixel(x, y);
          p[0] = -du * inv * 0.5f + 0.5f;
          p[1] = -dv * inv * 0.5f + 0.5f;
          p[2] = inv * 0.5f + 0.5f;
        }
      },
      8);
  return out;
}

}  // namespace forensim
