#include "wound/wound_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "spatial/closest_point.hpp"
#include "texture/closing_distance.hpp"
#include "texture/convex_hull.hpp"
#include "texture/gradient_edge.hpp"
#include "texture/polygon_fill.hpp"
#include "texture/value_noise.hpp"

namespace forensim {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Segment3 {
  Vec3 a, b;
  double r;
};

double point_segment_distance3(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0.0 ? (p - a).dot(ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

// Smallest distance from p to a stroke minus its radius (<= 0 inside the brushed shape).
double stroke_clearance(const std::vector<Segment3>& segments, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& s : segments) best = std::min(best, point_segment_distance3(p, s.a, s.b) - s.r);
  return best;
}

// Uniform grid over 3D points for nearest-point queries with an expanding search.
class PointGrid {
 public:
  PointGrid(const std::vector<Vec3>& points, double cell) : m_points(points), m_cell(cell) {
    for (std::size_t i = 0; i < points.size(); ++i) m_cells[key(cell_of(points[i]))].push_back(i);
    if (!points.empty()) {
      m_lo = m_hi = cell_of(points[0]);
      for (const auto& p : points) {
        const auto c = cell_of(p);
        for (int k = 0; k < 3; ++k) {
          m_lo[k] = std::min(m_lo[k], c[k]);
          m_hi[k] = std::max(m_hi[k], c[k]);
        }
      }
    }
  }
  // Distance from p to the nearest point, or +inf when none lies within max_distance.
  double nearest(const Vec3& p, double max_distance) const {
    double best = std::numeric_limits<double>::infinity();
    if (m_points.empty()) return best;
    const auto c = cell_of(p);
    long long max_ring = 0;
    for (int k = 0; k < 3; ++k) max_ring = std::max({max_ring, std::llabs(c[k] - m_lo[k]), std::llabs(c[k] - m_hi[k])});
    for (long long ring = 0; ring <= max_ring; ++ring) {
      // Points in rings beyond `ring` are at least (ring) cells away.
      const double lower_bound = static_cast<double>(ring - 1) * m_cell;
      if (best <= lower_bound || lower_bound > max_distance) break;
      for (long long dz = -ring; dz <= ring; ++dz) {
        for (long long dy = -ring; dy <= ring; ++dy) {
          for (long long dx = -ring; dx <= ring; ++dx) {
            if (std::max({std::llabs(dx), std::llabs(dy), std::llabs(dz)}) != ring) continue;
            const auto it = m_cells.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
            if (it == m_cells.end()) continue;
            for (std::size_t i : it->second) best = std::min(best, (m_points[i] - p).norm());
          }
        }
      }
    }
    return best <= max_distance ? best : std::numeric_limits<double>::infinity();
  }

 private:
  using Cell = std::array<long long, 3>;
  Cell cell_of(const Vec3& p) const {
    return {static_cast<long long>(std::floor(p.x() / m_cell)), static_cast<long long>(std::floor(p.y() / m_cell)),
            static_cast<long long>(std::floor(p.z() / m_cell))};
  }
  static std::uint64_t key(const Cell& c) {
    return (static_cast<std::uint64_t>(c[0] & 0x1FFFFF) << 42) | (static_cast<std::uint64_t>(c[1] & 0x1FFFFF) << 21) |
           static_cast<std::uint64_t>(c[2] & 0x1FFFFF);
  }
  const std::vector<Vec3>& m_points;
  double m_cell;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> m_cells;
  Cell m_lo{}, m_hi{};
};

Image crop_rgba(const Image& full, const TexelRect& r) {
  Image out = full.crop(r.x0, r.y0, r.width(), r.height()).with_channels(4);
  out.set_encoding(PixelEncoding::linear);
  return out;
}

double diameter_of(const std::vector<Vec3>& points) {
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 2048);
  double best = 0.0;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    for (std::size_t j = i + stride; j < points.size(); j += stride)
      best = std::max(best, (points[i] - points[j]).norm());
  }
  return best;
}

}  // namespace

namespace {

std::vector<CanvasTile> compute_tiles(const WoundCanvas& c) {
  const int tx = (c.width() + tiled_map_tile - 1) / tiled_map_tile;
  const int ty = (c.height() + tiled_map_tile - 1) / tiled_map_tile;
  std::vector<CanvasTile> tiles(static_cast<std::size_t>(tx) * static_cast<std::size_t>(ty));
  if (c.shape.width() != c.width() || c.shape.height() != c.height() || c.inside_mm.width() != c.width() ||
      c.inside_mm.height() != c.height() || c.outside_mm.width() != c.width() || c.outside_mm.height() != c.height()) {
    throw InputError("wound canvas", "maps", "shape and distances must be of the region's size");
  }
  parallel_for(
      0, tiles.size(),
      [&](std::size_t t) {
        CanvasTile& tile = tiles[t];
        const int x0 = static_cast<int>(t % static_cast<std::size_t>(tx)) * tiled_map_tile;
        const int y0 = static_cast<int>(t / static_cast<std::size_t>(tx)) * tiled_map_tile;
        const int x1 = std::min(x0 + tiled_map_tile, c.width()), y1 = std::min(y0 + tiled_map_tile, c.height());
        TexelRect box{x1, y1, x0, y0};
        for (int y = y0; y < y1; ++y) {
          const float* shape = c.shape.pixel(0, y);
          const float* in = c.inside_mm.pixel(0, y);
          const float* out = c.outside_mm.pixel(0, y);
          for (int x = x0; x < x1; ++x) {
            tile.max_inside_mm = std::max(tile.max_inside_mm, in[x]);
            if (shape[x] >= 0.5f) {
              ++tile.inside;
              box.x0 = std::min(box.x0, x);
              box.y0 = std::min(box.y0, y);
              box.x1 = std::max(box.x1, x + 1);
              box.y1 = std::max(box.y1, y + 1);
            } else if (out[x] < tile.min_outside_mm) {
              tile.min_outside_mm = out[x];
            }
          }
        }
        if (tile.inside > 0) tile.inside_box = box;
      },
      1);
  return tiles;
}

}  // namespace

void index_canvas_tiles(WoundCanvas& canvas) {
  canvas.tiles = compute_tiles(canvas);
}

const std::vector<CanvasTile>& canvas_tiles(const WoundCanvas& c, std::vector<CanvasTile>& scratch) {
  const std::size_t tx = static_cast<std::size_t>((c.width() + tiled_map_tile - 1) / tiled_map_tile);
  const std::size_t ty = static_cast<std::size_t>((c.height() + tiled_map_tile - 1) / tiled_map_tile);
  if (c.tiles.size() == tx * ty) return c.tiles;
  scratch = compute_tiles(c);
  return scratch;
}

TexelRect shape_bounds(const Image& shape) {
  TexelRect r{shape.width(), shape.height(), 0, 0};
  for (int y = 0; y < shape.height(); ++y) {
    for (int x = 0; x < shape.width(); ++x) {
      if (shape.at(x, y) < 0.5f) continue;
      r.x0 = std::min(r.x0, x);
      r.y0 = std::min(r.y0, y);
      r.x1 = std::max(r.x1, x + 1);
      r.y1 = std::max(r.y1, y + 1);
    }
  }
  if (r.empty()) return TexelRect{};
  return r;
}

double mesh_texels_per_mm(const TriMesh& mesh, int width, int height) {
  if (!mesh.has_uvs()) throw InputError("wound mesh", "uvs", "the mesh has no texture coordinates (UVs)");
  double uv_area = 0.0, area = 0.0;
  for (std::size_t f = 0; f < mesh.triangle_count(); ++f) {
    const auto& t = mesh.triangles[f];
    const auto& tu = mesh.triangle_uvs[f];
    const Vec3 e1 = mesh.positions[t[1]] - mesh.positions[t[0]];
    const Vec3 e2 = mesh.positions[t[2]] - mesh.positions[t[0]];
    area += 0.5 * e1.cross(e2).norm();
    const Vec2 a = mesh.uvs[tu[0]], b = mesh.uvs[tu[1]], c = mesh.uvs[tu[2]];
    const double u1 = (b.x() - a.x()) * width, v1 = (b.y() - a.y()) * height;
    const double u2 = (c.x() - a.x()) * width, v2 = (c.y() - a.y()) * height;
    uv_area += 0.5 * std::abs(u1 * v2 - u2 * v1);
  }
  if (!(area > 0.0) || !(uv_area > 0.0)) throw InputError("wound mesh", "uvs", "zero surface or UV area");
  return std::sqrt(uv_area / area);
}

WoundCanvas make_wound_canvas(const TriMesh& mesh, const UvRaster& raster, const std::vector<WoundStroke>& strokes,
                              const Image& upper_skin, const Image& lower_skin, const CanvasOptions& options) {
  const int W = raster.width, H = raster.height;
  if (upper_skin.width() != W || upper_skin.height() != H || lower_skin.width() != W || lower_skin.height() != H) {
    throw InputError("wound skin maps", "size", "the upper and lower skin maps must match the texture size");
  }
  if (strokes.empty()) throw InputError("wound strokes", "strokes", "no strokes given");
  std::vector<Segment3> segments;
  double max_radius = 0.0;
  for (std::size_t s = 0; s < strokes.size(); ++s) {
    const auto& st = strokes[s];
    if (st.points.empty() || !(st.radius_mm > 0.0) || !std::isfinite(st.radius_mm)) {
      throw InputError("wound strokes", "stroke " + std::to_string(s), "needs points and a positive radius");
    }
    max_radius = std::max(max_radius, st.radius_mm);
    for (std::size_t i = 0; i < st.points.size(); ++i) {
      segments.push_back({st.points[i], st.points[std::min(i + 1, st.points.size() - 1)], st.radius_mm});
      if (st.points.size() > 1 && i + 2 == st.points.size()) break;
    }
  }
  WoundCanvas c;
  c.full_width = W;
  c.full_height = H;
  c.seed = options.seed;
  c.distance = options.distance;
  c.texels_per_mm = options.texels_per_mm > 0.0 ? options.texels_per_mm : mesh_texels_per_mm(mesh, W, H);
  const double tpm = c.texels_per_mm;
  const double reach = std::max(options.reach_mm, 0.0);

  // Stroke points in texel coordinates (for the UV way and the hull).
  ClosestPointQuery closest(mesh);
  std::vector<std::pair<Vec2, double>> stroke_texels;  // texel point, radius in texels
  std::vector<std::array<std::size_t, 2>> texel_segments;
  for (std::size_t s = 0; s < strokes.size(); ++s) {
    const auto& st = strokes[s];
    const std::size_t first = stroke_texels.size();
    for (std::size_t k = 0; k < st.points.size(); ++k) {
      const Vec3& p = st.points[k];
      const auto hit = closest.query(p);
      if (!hit) throw InputError("wound strokes", "stroke " + std::to_string(s), "the mesh is empty");
      const double tolerance = std::max(2.0, st.radius_mm);
      if (hit->distance > tolerance) {
        throw InputError("wound strokes", "stroke " + std::to_string(s) + " point " + std::to_string(k),
                         "lies " + std::to_string(hit->distance) + " mm off the mesh (more than " +
                             std::to_string(tolerance) + " mm)");
      }
      stroke_texels.push_back({uv_to_pixel(uv_at(mesh, hit->triangle, hit->barycentric), W, H), st.radius_mm * tpm});
    }
    for (std::size_t i = first; i < stroke_texels.size(); ++i) {
      texel_segments.push_back({i, std::min(i + 1, stroke_texels.size() - 1)});
      if (stroke_texels.size() - first > 1 && i + 2 == stroke_texels.size()) break;
    }
  }
  std::vector<Vec2> hull;
  if (options.shape == ShapeMode::convex_hull) {
    std::vector<Vec2> pts;
    for (const auto& [p, r] : stroke_texels) {
      for (int k = 0; k < 16; ++k) {
        const double a = 2.0 * M_PI * k / 16.0;
        pts.push_back(p + r * Vec2(std::cos(a), std::sin(a)));
      }
    }
    hull = convex_hull(pts);
  }

  // Region: a texel rectangle holding the wound and everything within `reach` of it.
  long long x0 = W, y0 = H, x1 = -1, y1 = -1;
  auto grow = [&](double x, double y) {
    x0 = std::min<long long>(x0, static_cast<long long>(std::floor(x)));
    y0 = std::min<long long>(y0, static_cast<long long>(std::floor(y)));
    x1 = std::max<long long>(x1, static_cast<long long>(std::floor(x)));
    y1 = std::max<long long>(y1, static_cast<long long>(std::floor(y)));
  };
  if (options.distance == DistanceMode::surface) {
    Vec3 lo = segments[0].a, hi = lo;
    for (const auto& s : segments) {
      lo = lo.cwiseMin(s.a).cwiseMin(s.b);
      hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    }
    const double margin = max_radius + reach + 2.0 / tpm;
    lo.array() -= margin;
    hi.array() += margin;
    for (const auto& t : raster.texels) {
      if ((t.position.array() < lo.array()).any() || (t.position.array() > hi.array()).any()) continue;
      if (stroke_clearance(segments, t.position) <= reach + 2.0 / tpm) grow(t.x, t.y);
    }
  }
  if (options.distance == DistanceMode::uv || options.shape == ShapeMode::convex_hull) {
    const double m = reach * tpm + 2.0;
    for (const auto& [p, r] : stroke_texels) {
      grow(p.x() - r - m, p.y() - r - m);
      grow(p.x() + r + m, p.y() + r + m);
    }
  }
  x0 = std::max<long long>(x0 - 2, 0);
  y0 = std::max<long long>(y0 - 2, 0);
  x1 = std::min<long long>(x1 + 3, W);
  y1 = std::min<long long>(y1 + 3, H);
  if (x1 <= x0 || y1 <= y0) throw InputError("wound strokes", "strokes", "the strokes cover no texel of the mesh");
  c.region = TexelRect{static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1), static_cast<int>(y1)};
  const int w = c.region.width(), h = c.region.height();

  // Shape.
  c.shape = Image(w, h, 1, 0.0f, PixelEncoding::data);
  if (options.shape == ShapeMode::convex_hull) {
    std::vector<Vec2> local = hull;
    for (auto& p : local) p -= Vec2(c.region.x0, c.region.y0);
    fill_hull(c.shape, local);
  } else if (options.distance == DistanceMode::uv) {
    parallel_for(
        0, static_cast<std::size_t>(h),
        [&](std::size_t row) {
          const int y = static_cast<int>(row);
          for (int x = 0; x < w; ++x) {
            const Vec2 p(c.region.x0 + x + 0.5, c.region.y0 + y + 0.5);
            for (const auto& s : texel_segments) {
              const auto& [a, ra] = stroke_texels[s[0]];
              if (point_segment_distance(a, stroke_texels[s[1]].first, p) <= ra) {
                c.shape.at(x, y) = 1.0f;
                break;
              }
            }
          }
        },
        8);
  } else {
    parallel_for(
        0, static_cast<std::size_t>(h),
        [&](std::size_t row) {
          const int y = static_cast<int>(row);
          for (int x = 0; x < w; ++x) {
            const auto i = raster.at(c.region.x0 + x, c.region.y0 + y);
            if (i >= 0 && stroke_clearance(segments, raster.texels[static_cast<std::size_t>(i)].position) <= 0.0) {
              c.shape.at(x, y) = 1.0f;
            }
          }
        },
        8);
  }
  for (float v : c.shape.data()) c.wound_texels += v >= 0.5f ? 1u : 0u;
  if (c.wound_texels == 0) throw InputError("wound strokes", "strokes", "the wound covers no texel of the mesh");

  // Distances to the border.
  c.outside_mm = Image(w, h, 1, kInf, PixelEncoding::data);
  c.inside_mm = Image(w, h, 1, 0.0f, PixelEncoding::data);
  if (options.distance == DistanceMode::uv) {
    const Image out_d = edge_distance(c.shape, GradientSide::outside);
    const Image in_d = edge_distance(c.shape, GradientSide::inside);
    std::vector<Vec2> border;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const bool inside = c.shape.at(x, y) >= 0.5f;
        if (inside) {
          c.outside_mm.at(x, y) = 0.0f;
          c.inside_mm.at(x, y) = static_cast<float>((in_d.at(x, y) - 0.5) / tpm);
          if (in_d.at(x, y) <= 1.0f) border.push_back(Vec2(x + 0.5, y + 0.5));
        } else {
          c.outside_mm.at(x, y) = static_cast<float>((out_d.at(x, y) - 0.5) / tpm);
        }
      }
    }
    c.closing_distance_mm = closing_distance_of_points(border) / tpm;
  } else {
    // Border points: midpoints between 4-neighbouring covered texels on different sides of the shape.
    std::vector<Vec3> border;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const auto i = raster.at(c.region.x0 + x, c.region.y0 + y);
        if (i < 0) continue;
        const bool in = c.shape.at(x, y) >= 0.5f;
        const int nx[2] = {x + 1, x}, ny[2] = {y, y + 1};
        for (int k = 0; k < 2; ++k) {
          if (nx[k] >= w || ny[k] >= h) continue;
          const auto j = raster.at(c.region.x0 + nx[k], c.region.y0 + ny[k]);
          if (j < 0 || (c.shape.at(nx[k], ny[k]) >= 0.5f) == in) continue;
          border.push_back(0.5 * (raster.texels[static_cast<std::size_t>(i)].position +
                                  raster.texels[static_cast<std::size_t>(j)].position));
        }
      }
    }
    const PointGrid grid(border, std::max(2.0 / tpm, std::max(max_radius, reach) / 2.0));
    std::vector<std::uint8_t> covered(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
    parallel_for(
        0, static_cast<std::size_t>(h),
        [&](std::size_t row) {
          const int y = static_cast<int>(row);
          for (int x = 0; x < w; ++x) {
            const auto i = raster.at(c.region.x0 + x, c.region.y0 + y);
            if (i < 0) continue;
            covered[row * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = 1;
            const bool in = c.shape.at(x, y) >= 0.5f;
            const double d = grid.nearest(raster.texels[static_cast<std::size_t>(i)].position,
                                          in ? std::numeric_limits<double>::infinity() : reach + 1.0 / tpm);
            if (in) {
              c.outside_mm.at(x, y) = 0.0f;
              c.inside_mm.at(x, y) = std::isfinite(d) ? static_cast<float>(d) : 0.0f;
            } else {
              c.outside_mm.at(x, y) = static_cast<float>(d);
            }
          }
        },
        8);
    // Texels no triangle covers (the gutter) copy their covered neighbours, so bilinear lookups at chart
    // borders do not bleed healthy skin into the wound.
    dilate_gutter(c.shape, covered, 3);
    dilate_gutter(c.inside_mm, covered, 3);
    dilate_gutter(c.outside_mm, covered, 3);
    for (float& v : c.shape.data()) v = v >= 0.5f ? 1.0f : 0.0f;
    c.closing_distance_mm = diameter_of(border);
  }
  c.wound_box = shape_bounds(c.shape);
  c.upper_skin = crop_rgba(upper_skin, c.region);
  c.lower_skin = crop_rgba(lower_skin, c.region);
  index_canvas_tiles(c);
  return c;
}

void default_skin_maps(int width, int height, std::uint64_t seed, Image& upper_skin, Image& lower_skin) {
  ValueNoiseParams p;
  p.octaves = 5;
  p.persistence = 0.6;
  p.first_octave = 2;
  p.seed = seed ^ 0x5D1Bull;
  const Image n = value_noise(width, height, p);
  upper_skin = Image(width, height, 4, 1.0f, PixelEncoding::linear);
  lower_skin = Image(width, height, 4, 1.0f, PixelEncoding::linear);
  const Vec4f upper(0.56f, 0.36f, 0.27f, 1.0f), lower(0.62f, 0.26f, 0.23f, 1.0f);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float k = 0.92f + 0.16f * n.at(x, y);
      upper_skin.set_rgba(x, y, Vec4f(upper.x() * k, upper.y() * k, upper.z() * k, 1.0f));
      lower_skin.set_rgba(x, y, Vec4f(lower.x() * k, lower.y() * k, lower.z() * k, 1.0f));
    }
  }
}

MapSet skin_map_set(const Image& upper_skin, float skin_reflection) {
  MapSet set;
  set.color = upper_skin.with_channels(4);
  set.color.set_encoding(PixelEncoding::linear);
  set.reflection = Image(upper_skin.width(), upper_skin.height(), 1, skin_reflection, PixelEncoding::data);
  set.height_mm = Image(upper_skin.width(), upper_skin.height(), 1, 0.0f, PixelEncoding::data);
  return set;
}

}  // namespace forensim
