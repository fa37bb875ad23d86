#include "wound/flat_canvas.hpp"

#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "texture/closing_distance.hpp"
#include "texture/gradient_edge.hpp"

namespace forensim {

WoundCanvas make_flat_canvas(const Image& shape, double texels_per_mm, const Image& upper_skin, const Image& lower_skin,
                             std::uint64_t seed) {
  const int w = shape.width(), h = shape.height();
  if (shape.channels() != 1 || w == 0 || h == 0)
    throw InputError("flat wound canvas", "shape", "needs a 1-channel image");
  if (upper_skin.width() != w || upper_skin.height() != h || lower_skin.width() != w || lower_skin.height() != h) {
    throw InputError("flat wound canvas", "skin maps", "must have the shape's size");
  }
  if (!(texels_per_mm > 0.0) || !std::isfinite(texels_per_mm)) {
    throw InputError("flat wound canvas", "texels_per_mm", "must be a positive number");
  }
  WoundCanvas c;
  c.full_width = w;
  c.full_height = h;
  c.region = TexelRect{0, 0, w, h};
  c.texels_per_mm = texels_per_mm;
  c.seed = seed;
  c.distance = DistanceMode::uv;
  c.shape = Image(w, h, 1, 0.0f, PixelEncoding::data);
  for (std::size_t i = 0; i < c.shape.data().size(); ++i) c.shape.data()[i] = shape.data()[i] >= 0.5f ? 1.0f : 0.0f;
  const Image out_d = edge_distance(c.shape, GradientSide::outside);
  const Image in_d = edge_distance(c.shape, GradientSide::inside);
  c.outside_mm = Image(w, h, 1, 0.0f, PixelEncoding::data);
  c.inside_mm = Image(w, h, 1, 0.0f, PixelEncoding::data);
  std::vector<Vec2> border;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (c.shape.at(x, y) >= 0.5f) {
        ++c.wound_texels;
        c.inside_mm.at(x, y) = static_cast<float>((in_d.at(x, y) - 0.5) / texels_per_mm);
        if (in_d.at(x, y) <= 1.0f) border.push_back(Vec2(x + 0.5, y + 0.5));
      } else {
        c.outside_mm.at(x, y) = static_cast<float>((out_d.at(x, y) - 0.5) / texels_per_mm);
      }
    }
  if (c.wound_texels == 0) throw InputError("flat wound canvas", "shape", "has no texel inside the wound");
  c.closing_distance_mm = closing_distance_of_points(border) / texels_per_mm;
  c.wound_box = shape_bounds(c.shape);
  c.upper_skin = upper_skin.with_channels(4);
  c.upper_skin.set_encoding(PixelEncoding::linear);
  c.lower_skin = lower_skin.with_channels(4);
  c.lower_skin.set_encoding(PixelEncoding::linear);
  index_canvas_tiles(c);
  return c;
}

}  // namespace forensim
