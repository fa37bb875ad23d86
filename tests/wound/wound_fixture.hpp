#pragma once
/// A small wound for the wound tests: a stroke across the UV seam of a thin cylinder, painted at 128^2.

#include <cmath>
#include <memory>

#include "texture/uv_bake.hpp"
#include "wound/abrasion.hpp"
#include "wound/uv_cylinder.hpp"
#include "wound/wound_canvas.hpp"

namespace forensim::test {

/// Point on the fixture cylinder (radius 10 mm) at angle `a` (radians) and height z (mm).
inline Vec3 cylinder_point(double a, double z) {
  return Vec3(10.0 * std::cos(a), 10.0 * std::sin(a), z);
}

inline TriMesh fixture_mesh() {
  return make_uv_cylinder(10.0, 60.0, 48, 24);
}

/// Canvas of a wound of two strokes (a bent one across the seam and a dot) at `size`^2.
inline std::shared_ptr<WoundCanvas> fixture_canvas(int size = 128, DistanceMode mode = DistanceMode::surface,
                                                   ShapeMode shape = ShapeMode::strokes, std::uint64_t seed = 7) {
  const TriMesh mesh = fixture_mesh();
  const UvRaster raster = rasterize_uv(mesh, size, size);
  Image upper, lower;
  default_skin_maps(size, size, seed, upper, lower);
  std::vector<WoundStroke> strokes(2);
  strokes[0].points = {cylinder_point(-0.6, 22.0), cylinder_point(0.0, 28.0), cylinder_point(0.5, 26.0)};
  strokes[0].radius_mm = 3.0;
  strokes[1].points = {cylinder_point(1.6, 36.0)};
  strokes[1].radius_mm = 2.5;
  CanvasOptions options;
  options.distance = mode;
  options.shape = shape;
  options.seed = seed;
  options.reach_mm = AbrasionParams{}.reach_mm();
  return std::make_shared<WoundCanvas>(make_wound_canvas(mesh, raster, strokes, upper, lower, options));
}

}  // namespace forensim::test
