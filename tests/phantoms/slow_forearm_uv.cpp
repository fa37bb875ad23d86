#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <unordered_map>

#include "core/timer.hpp"
#include "image/png_io.hpp"
#include "mesh_processing/uv_atlas.hpp"
#include "phantoms/forearm_uv.hpp"
#include "phantoms/skin_maps.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {

/// The full-resolution model (1.5 mm voxels, 2 mm edges, 2048^2) and its maps, built once.
struct Full {
  ForearmUvModel model;
  SkinMaps maps;
  Full() {
    model = make_forearm_uv();
    maps = make_skin_maps(model.mesh, 2048, 1);
  }
};

const Full& full() {
  static const Full instance;
  return instance;
}

/// Orthographic picture of the textured skin seen from above (dorsal, top half) and from below (palmar,
/// bottom half): per-pixel UV lookup of the epidermis map, Lambert shading with the interpolated normal. A few
/// lines of z-buffering so this test needs no renderer.
Image render_views(const TriMesh& mesh, const Image& albedo, double px_per_mm) {
  const double x0 = -5.0, x1 = 420.0, y0 = -50.0, y1 = 92.0;
  const int w = static_cast<int>((x1 - x0) * px_per_mm), h = static_cast<int>((y1 - y0) * px_per_mm);
  Image picture(w, 2 * h, 3, 0.08f, PixelEncoding::linear);
  const Vec3 light = Vec3(0.3, 0.4, 1.0).normalized();
  for (int view = 0; view < 2; ++view) {
    std::vector<double> depth(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), -1e30);
    const double sign = view == 0 ? 1.0 : -1.0;  // +z toward the viewer from above, -z from below
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      Vec2 s[3];
      double z[3];
      for (std::size_t k = 0; k < 3; ++k) {
        const Vec3& p = mesh.positions[static_cast<std::size_t>(mesh.triangles[t][k])];
        s[k] = Vec2((p.x() - x0) * px_per_mm, view == 0 ? (y1 - p.y()) * px_per_mm : (p.y() - y0) * px_per_mm);
        z[k] = sign * p.z();
      }
      const double area = (s[1] - s[0]).x() * (s[2] - s[0]).y() - (s[1] - s[0]).y() * (s[2] - s[0]).x();
      if (std::abs(area) < 1e-12) continue;
      const int bx0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].x(), s[1].x(), s[2].x()}))));
      const int bx1 = std::min(w - 1, static_cast<int>(std::ceil(std::max({s[0].x(), s[1].x(), s[2].x()}))));
      const int by0 = std::max(0, static_cast<int>(std::floor(std::min({s[0].y(), s[1].y(), s[2].y()}))));
      const int by1 = std::min(h - 1, static_cast<int>(std::ceil(std::max({s[0].y(), s[1].y(), s[2].y()}))));
      for (int y = by0; y <= by1; ++y) {
        for (int x = bx0; x <= bx1; ++x) {
          const Vec2 c(x + 0.5, y + 0.5);
          const auto edge = [&](const Vec2& a, const Vec2& b) {
            return ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()) / area;
          };
          const double w0 = edge(s[1], s[2]), w1 = edge(s[2], s[0]), w2 = 1.0 - w0 - w1;
          if (w0 < 0 || w1 < 0 || w2 < 0) continue;
          const double d = w0 * z[0] + w1 * z[1] + w2 * z[2];
          double& stored =
              depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
          if (d <= stored) continue;
          stored = d;
          Vec3 n = Vec3::Zero();
          Vec2 uv = Vec2::Zero();
          const double wt[3] = {w0, w1, w2};
          for (std::size_t k = 0; k < 3; ++k) {
            n += wt[k] * mesh.normals[static_cast<std::size_t>(mesh.triangles[t][k])];
            uv += wt[k] * mesh.uvs[static_cast<std::size_t>(mesh.triangle_uvs[t][k])];
          }
          n.normalize();
          if (view == 1) n.z() = -n.z(), n.y() = -n.y();  // seen from below: mirror into the view frame
          const Vec4f a = albedo.sample_uv(uv, WrapMode::clamp);
          const float shade = static_cast<float>(0.2 + 0.8 * std::max(0.0, n.dot(light)));
          for (int ch = 0; ch < 3; ++ch) picture.at(x, y + view * h, ch) = a[ch] * shade;
        }
      }
    }
  }
  return picture;
}

}  // namespace

TEST(ForearmUvSlow, FullLayoutMeetsTheTargets) {
  const ForearmUvModel& m = full().model;
  const ForearmUvStats& s = m.stats;
  std::cout << "forearm-uv: " << m.mesh.positions.size() << " vertices, " << m.mesh.triangles.size() << " triangles, "
            << m.chart_names.size() << " charts; L2 stretch " << s.l2_stretch << " (worst chart "
            << s.max_chart_l2_stretch << "), area distortion " << s.area_distortion << ", packing "
            << s.packing_efficiency << ", " << s.mm_per_uv_unit / 2048.0 << " mm per texel at 2048; seams "
            << s.seam_length_mm << " mm, hidden " << s.hidden_seam_fraction << "; surface " << m.seconds_surface
            << " s, atlas " << m.seconds_atlas << " s\n";
  for (std::size_t c = 0; c < m.chart_names.size(); ++c) {
    std::cout << "  chart " << c << " " << m.chart_names[c] << ": L2 " << s.chart_l2_stretch[c] << " ("
              << s.chart_flattening[c] << ")\n";
  }
  EXPECT_EQ(m.chart_names.size(), 13u);
  EXPECT_TRUE(s.overlap_free);
  EXPECT_FALSE(uv_triangles_overlap(m.mesh, 4096));
  EXPECT_LE(s.l2_stretch, 1.05);            // measured 1.0009
  EXPECT_LE(s.max_chart_l2_stretch, 1.10);  // measured 1.005
  EXPECT_GE(s.hidden_seam_fraction, 0.8);   // measured 0.88
  EXPECT_EQ(uv_outside_unit_square(m.mesh, 8.0 / 2048.0 - 1e-9), 0u);
  EXPECT_GT(m.mesh.triangles.size(), 40000u);
}

TEST(ForearmUvSlow, FullMapsAreSeamlessAndWritten) {
  const Full& f = full();
  const SkinMaps& maps = f.maps;
  std::cout << "skin maps 2048^2: " << maps.seconds << " s, texel " << maps.texel_mm << " mm\n";
  // Seam continuity at full resolution: the epidermis sampled from both charts at each seam edge's midpoint.
  const TriMesh& mesh = f.model.mesh;
  std::unordered_map<std::uint64_t, std::pair<std::size_t, std::size_t>> first;
  std::vector<double> diff;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const Index a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      const std::uint64_t key =
          (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint32_t>(std::max(a, b));
      auto [it, inserted] = first.try_emplace(key, t, k);
      if (inserted) continue;
      const auto [u, j] = it->second;
      if (f.model.triangle_chart[u] == f.model.triangle_chart[t]) continue;
      const auto uv = [&](std::size_t tri, std::size_t corner) {
        return mesh.uvs[static_cast<std::size_t>(mesh.triangle_uvs[tri][corner])];
      };
      const Vec2 m0 = 0.5 * (uv(t, k) + uv(t, (k + 1) % 3)), m1 = 0.5 * (uv(u, j) + uv(u, (j + 1) % 3));
      diff.push_back((maps.epidermis.sample_uv(m0, WrapMode::clamp) - maps.epidermis.sample_uv(m1, WrapMode::clamp))
                         .head<3>()
                         .norm());
    }
  }
  std::sort(diff.begin(), diff.end());
  const double median = diff[diff.size() / 2], p95 = diff[diff.size() * 95 / 100];
  std::cout << "seam colour difference (linear RGB): median " << median << ", 95th percentile " << p95 << " over "
            << diff.size() << " seam edges\n";
  EXPECT_LT(median, 0.01);
  EXPECT_LT(p95, 0.05);

  const std::filesystem::path folder = test::scratch_dir("forearm_uv_maps");
  write_skin_maps(maps, folder);
  const Image picture = render_views(mesh, maps.epidermis, 4.0);
  write_png(folder / "forearm_uv_render.png", picture);
  for (const char* name : {"epidermis.png", "dermis.png", "specular.png", "normal.png", "forearm_uv_render.png"}) {
    EXPECT_TRUE(std::filesystem::exists(folder / name));
    std::cout << "wrote " << (folder / name).string() << "\n";
  }
  const Image back = read_png(folder / "normal.png", PngTransfer::identity);
  EXPECT_EQ(back.width(), 2048);
}
