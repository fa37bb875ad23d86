#include "texture/uv_bake.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {
namespace {

double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

const Vec2& corner_uv(const TriMesh& mesh, Index triangle, int corner) {
  return mesh.uvs[static_cast<std::size_t>(
      mesh.triangle_uvs[static_cast<std::size_t>(triangle)][static_cast<std::size_t>(corner)])];
}

const Vec3& corner_position(const TriMesh& mesh, Index triangle, int corner) {
  return mesh.positions[static_cast<std::size_t>(
      mesh.triangles[static_cast<std::size_t>(triangle)][static_cast<std::size_t>(corner)])];
}

}  // namespace

void triangle_tangents(const TriMesh& mesh, Index triangle, Vec3& dp_du, Vec3& dp_dv) {
  const Vec3 e1 = corner_position(mesh, triangle, 1) - corner_position(mesh, triangle, 0);
  const Vec3 e2 = corner_position(mesh, triangle, 2) - corner_position(mesh, triangle, 0);
  const Vec2 d1 = corner_uv(mesh, triangle, 1) - corner_uv(mesh, triangle, 0);
  const Vec2 d2 = corner_uv(mesh, triangle, 2) - corner_uv(mesh, triangle, 0);
  const double det = cross2(d1, d2);
  if (det == 0.0 || !std::isfinite(det)) {
    dp_du.setZero();
    dp_dv.setZero();
    return;
  }
  dp_du = (e1 * d2.y() - e2 * d1.y()) / det;
  dp_dv = (e2 * d1.x() - e1 * d2.x()) / det;
}

UvRaster rasterize_uv(const TriMesh& mesh, int width, int height, int padding_texels) {
  mesh.validate("mesh to bake");
  require_input(mesh.has_uvs(), "mesh to bake", "", "has no UVs");
  require_input(width >= 1 && width <= 16384 && height >= 1 && height <= 16384, "UV raster", "size",
                "must be in [1, 16384] per side, got " + std::to_string(width) + " x " + std::to_string(height));
  UvRaster raster;
  raster.width = width;
  raster.height = height;
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<Index> texel_triangle(count, -1);
  std::vector<Vec3> texel_weights(count);
  // Serial in triangle order so that the lower index wins shared edges: deterministic.
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto ti = static_cast<Index>(t);
    Vec2 p[3];
    for (int k = 0; k < 3; ++k) {
      const Vec2& uv = corner_uv(mesh, ti, k);
      p[k] = Vec2(uv.x() * width, (1.0 - uv.y()) * height);
    }
    const double area2 = cross2(p[1] - p[0], p[2] - p[0]);
    if (area2 == 0.0 || !std::isfinite(area2)) continue;
    const double x0 = std::min({p[0].x(), p[1].x(), p[2].x()}), x1 = std::max({p[0].x(), p[1].x(), p[2].x()});
    const double y0 = std::min({p[0].y(), p[1].y(), p[2].y()}), y1 = std::max({p[0].y(), p[1].y(), p[2].y()});
    const int ix0 = std::max(0, static_cast<int>(std::floor(x0 - 0.5)));
    const int ix1 = std::min(width - 1, static_cast<int>(std::ceil(x1)));
    const int iy0 = std::max(0, static_cast<int>(std::floor(y0 - 0.5)));
    const int iy1 = std::min(height - 1, static_cast<int>(std::ceil(y1)));
    for (int iy = iy0; iy <= iy1; ++iy) {
      for (int ix = ix0; ix <= ix1; ++ix) {
        const Vec2 c(ix + 0.5, iy + 0.5);
        const double w0 = cross2(p[1] - c, p[2] - c) / area2;
        const double w1 = cross2(p[2] - c, p[0] - c) / area2;
        const double w2 = 1.0 - w0 - w1;
        if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
        const std::size_t i =
            static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) + static_cast<std::size_t>(ix);
        if (texel_triangle[i] >= 0) continue;
        texel_triangle[i] = ti;
        texel_weights[i] = Vec3(std::max(w0, 0.0), std::max(w1, 0.0), std::max(w2, 0.0));
        texel_weights[i] /= texel_weights[i].sum();
      }
    }
  }
  require_input(padding_texels >= 0 && padding_texels <= 64, "UV raster", "padding_texels",
                "must be in [0, 64], got " + std::to_string(padding_texels));
  // Padding: rings of texels just outside the triangles take the best-fitting neighbouring texel's triangle,
  // with barycentrics extrapolated, so bilinear lookups at chart borders read true values, not blends.
  std::vector<std::uint8_t> inside(count, 0);
  for (std::size_t i = 0; i < count; ++i) inside[i] = texel_triangle[i] >= 0 ? 1 : 0;
  const auto weights_at = [&](Index t, int ix, int iy) {
    Vec2 p[3];
    for (int k = 0; k < 3; ++k) {
      const Vec2& uv = corner_uv(mesh, t, k);
      p[k] = Vec2(uv.x() * width, (1.0 - uv.y()) * height);
    }
    const Vec2 c(ix + 0.5, iy + 0.5);
    const double area2 = cross2(p[1] - p[0], p[2] - p[0]);
    const double w0 = cross2(p[1] - c, p[2] - c) / area2, w1 = cross2(p[2] - c, p[0] - c) / area2;
    return Vec3(w0, w1, 1.0 - w0 - w1);
  };
  for (int ring = 0; ring < padding_texels; ++ring) {
    std::vector<std::pair<std::size_t, Index>> found;
    for (int iy = 0; iy < height; ++iy) {
      for (int ix = 0; ix < width; ++ix) {
        const std::size_t i =
            static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) + static_cast<std::size_t>(ix);
        if (texel_triangle[i] >= 0) continue;
        Index best = -1;
        double best_outside = std::numeric_limits<double>::infinity();
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = ix + dx, y = iy + dy;
            if (x < 0 || y < 0 || x >= width || y >= height) continue;
            const Index t = texel_triangle[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                           static_cast<std::size_t>(x)];
            if (t < 0 || t == best) continue;
            const double outside = -weights_at(t, ix, iy).minCoeff();
            if (outside < best_outside || (outside == best_outside && t < best)) {
              best_outside = outside;
              best = t;
            }
          }
        }
        if (best >= 0) found.emplace_back(i, best);
      }
    }
    for (const auto& [i, t] : found) {
      texel_triangle[i] = t;
      texel_weights[i] = weights_at(t, static_cast<int>(i % static_cast<std::size_t>(width)),
                                    static_cast<int>(i / static_cast<std::size_t>(width)));
    }
  }
  raster.map.assign(count, -1);
  std::size_t covered = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (texel_triangle[i] >= 0) raster.map[i] = static_cast<std::int32_t>(covered++);
  }
  raster.texels.resize(covered);
  // Per-triangle tangents once.
  std::vector<Vec3> dp_du(mesh.triangles.size()), dp_dv(mesh.triangles.size()), face_normal(mesh.triangles.size());
  parallel_for(0, mesh.triangles.size(), [&](std::size_t t) {
    triangle_tangents(mesh, static_cast<Index>(t), dp_du[t], dp_dv[t]);
    const Vec3 n =
        (corner_position(mesh, static_cast<Index>(t), 1) - corner_position(mesh, static_cast<Index>(t), 0))
            .cross(corner_position(mesh, static_cast<Index>(t), 2) - corner_position(mesh, static_cast<Index>(t), 0));
    face_normal[t] = n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3(Vec3::UnitZ());
  });
  parallel_for(0, count, [&](std::size_t i) {
    const std::int32_t k = raster.map[i];
    if (k < 0) return;
    UvTexel& texel = raster.texels[static_cast<std::size_t>(k)];
    texel.x = static_cast<int>(i % static_cast<std::size_t>(width));
    texel.y = static_cast<int>(i / static_cast<std::size_t>(width));
    texel.triangle = texel_triangle[i];
    texel.barycentric = texel_weights[i];
    texel.inside = inside[i] != 0;
    const auto t = static_cast<std::size_t>(texel.triangle);
    const Tri& f = mesh.triangles[t];
    texel.position = Vec3::Zero();
    Vec3 normal = Vec3::Zero();
    for (std::size_t c = 0; c < 3; ++c) {
      texel.position +=
          texel.barycentric[static_cast<Eigen::Index>(c)] * mesh.positions[static_cast<std::size_t>(f[c])];
      if (mesh.has_normals())
        normal += texel.barycentric[static_cast<Eigen::Index>(c)] * mesh.normals[static_cast<std::size_t>(f[c])];
    }
    texel.normal = normal.norm() > 1e-12 ? Vec3(normal.normalized()) : face_normal[t];
    // Tangent: dP/du without its normal component; falls back to any unit vector orthogonal to the normal.
    Vec3 tangent = dp_du[t] - texel.normal * texel.normal.dot(dp_du[t]);
    if (tangent.norm() < 1e-12 * std::max(1.0, dp_du[t].norm())) {
      tangent = texel.normal.unitOrthogonal();
    }
    texel.tangent = tangent.normalized();
    texel.bitangent = texel.normal.cross(texel.tangent);
    if (texel.bitangent.dot(dp_dv[t]) < 0.0) texel.bitangent = -texel.bitangent;  // mirrored UVs
  });
  return raster;
}

std::vector<std::uint8_t> coverage(const UvRaster& raster) {
  std::vector<std::uint8_t> flags(raster.map.size(), 0);
  for (std::size_t i = 0; i < flags.size(); ++i) flags[i] = raster.map[i] >= 0 ? 1 : 0;
  return flags;
}

void dilate_gutter(Image& image, const std::vector<std::uint8_t>& covered, int texels) {
  const int w = image.width(), h = image.height(), channels = image.channels();
  require_input(covered.size() == static_cast<std::size_t>(w) * static_cast<std::size_t>(h), "gutter dilation",
                "coverage",
                "has " + std::to_string(covered.size()) + " flags for a " + std::to_string(w) + " x " +
                    std::to_string(h) + " image");
  std::vector<std::uint8_t> filled = covered;
  std::vector<std::uint8_t> next = filled;
  for (int ring = 0; ring < texels; ++ring) {
    // Reads only `filled` and pixels filled in earlier rings, writes only pixels not yet filled: the result
    // does not depend on the order rows are processed in.
    parallel_for(
        0, static_cast<std::size_t>(h),
        [&](std::size_t row) {
          const int y = static_cast<int>(row);
          for (int x = 0; x < w; ++x) {
            const std::size_t i =
                static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
            if (filled[i]) continue;
            float sum[4] = {0, 0, 0, 0};
            int n = 0;
            for (int dy = -1; dy <= 1; ++dy) {
              for (int dx = -1; dx <= 1; ++dx) {
                const int xx = x + dx, yy = y + dy;
                if ((dx == 0 && dy == 0) || xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
                if (!filled[static_cast<std::size_t>(yy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(xx)])
                  continue;
                const float* p = image.pixel(xx, yy);
                for (int c = 0; c < channels; ++c) sum[c] += p[c];
                ++n;
              }
            }
            if (n == 0) continue;
            float* q = image.pixel(x, y);
            for (int c = 0; c < channels; ++c) q[c] = sum[c] / static_cast<float>(n);
            next[i] = 1;
          }
        },
        16);
    filled = next;
  }
}

Image bake(const UvRaster& raster, int channels, const std::function<Vec4f(const UvTexel&)>& shader, int dilate_texels,
           const Vec4f& background, PixelEncoding encoding) {
  Image image(raster.width, raster.height, channels, 0.0f, encoding);
  image.fill(background);
  parallel_for(
      0, raster.texels.size(),
      [&](std::size_t i) {
        const UvTexel& texel = raster.texels[i];
        image.set_rgba(texel.x, texel.y, shader(texel));
      },
      1024);
  if (dilate_texels > 0) dilate_gutter(image, coverage(raster), dilate_texels);
  return image;
}

Vec2 uv_at(const TriMesh& mesh, Index triangle, const Vec3& barycentric) {
  require_input(mesh.has_uvs(), "mesh with UVs", "", "has no UVs");
  require_input(triangle >= 0 && static_cast<std::size_t>(triangle) < mesh.triangles.size(), "mesh with UVs",
                "triangle " + std::to_string(triangle), "does not exist");
  return barycentric.x() * corner_uv(mesh, triangle, 0) + barycentric.y() * corner_uv(mesh, triangle, 1) +
         barycentric.z() * corner_uv(mesh, triangle, 2);
}

Vec2 uv_to_pixel(const Vec2& uv, int width, int height) {
  return Vec2(uv.x() * width, (1.0 - uv.y()) * height);
}

}  // namespace forensim
