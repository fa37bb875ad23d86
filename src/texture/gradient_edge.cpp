#include "texture/gradient_edge.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "texture/distance_transform.hpp"
#include "texture/image_ops.hpp"

namespace forensim {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

bool on_side(const Image& shape, int x, int y, GradientSide side, float threshold) {
  const bool inside = shape.at(x, y, 0) >= threshold;
  return side == GradientSide::inside ? inside : !inside;
}

void require_thickness(double thickness) {
  require_input(std::isfinite(thickness) && thickness > 0.0, "gradient edge", "thickness",
                "must be a finite positive number of texels");
}

// Lines 7 to 12 of Algorithm 3.4 for one texel at distance d.
Vec4f gradient_color(double d, double thickness, const Vec4f& from, const Vec4f& to) {
  if (!(d <= thickness)) return {0.0f, 0.0f, 0.0f, 1.0f};
  return blend_lerp(from, to, static_cast<float>(d / thickness));
}

}  // namespace

double point_segment_distance(const Vec2& l1, const Vec2& l2, const Vec2& p) {
  Vec2 v = l2 - l1;                                   // line 1
  if ((l1 - p).dot(v) > 0.0) return (p - l1).norm();  // lines 2 to 5
  v = l1 - l2;                                        // line 6
  if ((l2 - p).dot(v) > 0.0) return (p - l2).norm();  // lines 7 to 10
  const Vec2 normal(v[1], -v[0]);                     // line 11
  const double length = normal.norm();
  if (length == 0.0) return (p - l1).norm();       // degenerate segment
  return std::abs((normal / length).dot(p - l1));  // lines 12 to 14
}

double polygon_edge_distance(const std::vector<Vec2>& hull, const Vec2& p) {
  if (hull.empty()) return infinity;
  if (hull.size() == 1) return (p - hull[0]).norm();
  double best = infinity;
  for (std::size_t i = 0; i < hull.size(); ++i)
    best = std::min(best, point_segment_distance(hull[i], hull[(i + 1) % hull.size()], p));
  return best;
}

Image edge_distance(const Image& shape, GradientSide side, float threshold) {
  // The texels on the other side are the features: inside ones (binary_mask) for an outward gradient.
  std::vector<std::uint8_t> other = binary_mask(shape, threshold);
  if (side == GradientSide::inside)
    for (std::uint8_t& b : other) b = b ? 0 : 1;
  const std::vector<double> squared = squared_distance_transform(other, shape.width(), shape.height());
  Image out(shape.width(), shape.height(), 1, 0.0f, PixelEncoding::data);
  float* values = out.data().data();
  parallel_for_chunks(0, squared.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      values[i] = other[i] ? std::numeric_limits<float>::infinity() : static_cast<float>(std::sqrt(squared[i]));
  });
  return out;
}

Image draw_gradient_edge(const Image& shape, double thickness, GradientSide side, const Vec4f& color_from,
                         const Vec4f& color_to, float threshold) {
  require_thickness(thickness);
  const Image distance = edge_distance(shape, side, threshold);
  Image out(shape.width(), shape.height(), 4, 0.0f, PixelEncoding::linear);
  parallel_for(
      0, static_cast<std::size_t>(shape.height()),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        for (int x = 0; x < shape.width(); ++x)
          out.set_rgba(x, y, gradient_color(static_cast<double>(distance.at(x, y)), thickness, color_from, color_to));
      },
      8);
  return out;
}

Image draw_gradient_edge_hull(const std::vector<Vec2>& hull, const Image& shape, double thickness, GradientSide side,
                              const Vec4f& color_from, const Vec4f& color_to, float threshold) {
  require_thickness(thickness);
  Image out(shape.width(), shape.height(), 4, 0.0f, PixelEncoding::linear);
  parallel_for(
      0, static_cast<std::size_t>(shape.height()),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        for (int x = 0; x < shape.width(); ++x) {
          if (!on_side(shape, x, y, side, threshold)) {  // lines 2 to 5
            out.set_rgba(x, y, {0.0f, 0.0f, 0.0f, 1.0f});
            continue;
          }
          const double d = polygon_edge_distance(hull, Vec2(x + 0.5, y + 0.5));  // line 6
          out.set_rgba(x, y, gradient_color(d, thickness, color_from, color_to));
        }
      },
      4);
  return out;
}

}  // namespace forensim
