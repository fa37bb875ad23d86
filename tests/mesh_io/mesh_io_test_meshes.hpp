#pragma once
/// Test meshes and comparisons shared by the mesh_io tests: a UV-mapped box whose six faces are separate
/// UV islands (so every box edge is a UV seam), and an order-independent comparison of two meshes.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "geometry/primitives.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim::test {

/// A 2x2 RGBA PNG (red, green / blue, white), encoded by hand so the tests need no image library.
inline std::string tiny_png() {
  static const unsigned char bytes[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00, 0x00,
      0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06, 0x00, 0x00, 0x00, 0x72, 0xb6, 0x0d, 0x24, 0x00, 0x00, 0x00, 0x12, 0x49,
      0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8, 0xcf, 0xc0, 0xf0, 0x1f, 0x0c, 0x81, 0x34, 0x18, 0x00, 0x00, 0x49, 0xc8,
      0x09, 0xf7, 0xf9, 0xab, 0xb6, 0x0d, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  return std::string(reinterpret_cast<const char*>(bytes), sizeof bytes);
}

/// Box from `min` to `max` (mm) with n x n quads per face; each face is its own UV island in a 3 x 2 atlas,
/// vertex normals point away from the centre, colours are exact multiples of 1/255.
inline TriMesh make_uv_box(const Vec3& min, const Vec3& max, int n = 1) {
  TriMesh mesh = make_box_mesh(min, max, n);
  mesh.normals.clear();
  mesh.uvs.clear();
  mesh.triangle_uvs.clear();
  const Vec3 size = max - min;
  std::map<std::pair<double, double>, Index> uv_index;
  for (const Tri& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Vec3 normal = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
    int axis = 0;
    normal.cwiseAbs().maxCoeff(&axis);
    const int face = 2 * axis + (normal[axis] > 0 ? 1 : 0);
    const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
    Tri corner_uvs{};
    for (int c = 0; c < 3; ++c) {
      const Vec3& p = mesh.positions[t[c]];
      const double u = (face % 3 + 0.1 + 0.8 * (p[u_axis] - min[u_axis]) / size[u_axis]) / 3.0;
      const double v = (face / 3 + 0.1 + 0.8 * (p[v_axis] - min[v_axis]) / size[v_axis]) / 2.0;
      const auto [it, inserted] = uv_index.try_emplace({u, v}, static_cast<Index>(mesh.uvs.size()));
      if (inserted) mesh.uvs.emplace_back(u, v);
      corner_uvs[c] = it->second;
    }
    mesh.triangle_uvs.push_back(corner_uvs);
  }
  const Vec3 center = 0.5 * (min + max);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    mesh.normals.push_back((mesh.positions[v] - center).normalized());
    const float r = static_cast<float>((37 * v) % 256) / 255.0f;
    mesh.colors.emplace_back(r, 1.0f - r, 0.2f, 1.0f);
  }
  mesh.material.name = "skin";
  mesh.material.base_color = Vec4f(0.8f, 0.6f, 0.5f, 1.0f);
  mesh.material.roughness = 0.7f;
  mesh.material.metallic = 0.0f;
  return mesh;
}

/// For each vertex of `actual`, the vertex of `expected` at the same position (within `tolerance`), or -1.
inline std::vector<Index> match_vertices(const TriMesh& expected, const TriMesh& actual, double tolerance) {
  std::vector<Index> match(actual.positions.size(), -1);
  for (std::size_t i = 0; i < actual.positions.size(); ++i) {
    for (std::size_t j = 0; j < expected.positions.size(); ++j) {
      if ((actual.positions[i] - expected.positions[j]).norm() <= tolerance) {
        match[i] = static_cast<Index>(j);
        break;
      }
    }
  }
  return match;
}

/// Checks that `actual` is `expected` up to vertex and triangle order: same welded vertex count, same
/// positions, same triangles with the same orientation, and (when `check_uvs`) the same UV at each corner
/// of each triangle, which is what a UV seam must preserve. Normals and colours per vertex when asked.
inline void expect_same_mesh(const TriMesh& expected, const TriMesh& actual, double tolerance, bool check_uvs,
                             bool check_normals, bool check_colors) {
  ASSERT_EQ(actual.vertex_count(), expected.vertex_count());
  ASSERT_EQ(actual.triangle_count(), expected.triangle_count());
  const std::vector<Index> match = match_vertices(expected, actual, tolerance);
  for (std::size_t i = 0; i < match.size(); ++i) ASSERT_GE(match[i], 0) << "vertex " << i << " has no match";

  // Triangles keyed by their vertex cycle starting at the smallest index (keeps orientation).
  const auto canonical = [](Tri t, Tri uv) {
    const int first = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
    std::rotate(t.begin(), t.begin() + first, t.end());
    std::rotate(uv.begin(), uv.begin() + first, uv.end());
    return std::make_pair(t, uv);
  };
  std::map<Tri, Tri> expected_uvs;
  for (std::size_t f = 0; f < expected.triangle_count(); ++f) {
    const auto [t, uv] = canonical(expected.triangles[f], expected.has_uvs() ? expected.triangle_uvs[f] : Tri{});
    expected_uvs[t] = uv;
  }
  ASSERT_EQ(actual.has_uvs(), check_uvs && expected.has_uvs());
  for (std::size_t f = 0; f < actual.triangle_count(); ++f) {
    Tri mapped{};
    for (int c = 0; c < 3; ++c) mapped[c] = match[actual.triangles[f][c]];
    const auto [t, uv] = canonical(mapped, actual.has_uvs() ? actual.triangle_uvs[f] : Tri{});
    const auto it = expected_uvs.find(t);
    ASSERT_NE(it, expected_uvs.end()) << "triangle " << f << " is missing or flipped";
    if (!check_uvs) continue;
    for (int c = 0; c < 3; ++c) {
      const Vec2& want = expected.uvs[it->second[c]];
      const Vec2& got = actual.uvs[uv[c]];
      EXPECT_NEAR(got[0], want[0], 1e-6) << "triangle " << f << " corner " << c;
      EXPECT_NEAR(got[1], want[1], 1e-6) << "triangle " << f << " corner " << c;
    }
  }
  if (check_normals) {
    ASSERT_TRUE(actual.has_normals());
    for (std::size_t i = 0; i < match.size(); ++i) {
      EXPECT_LT((actual.normals[i] - expected.normals[match[i]]).norm(), 1e-5) << "normal " << i;
    }
  }
  if (check_colors) {
    ASSERT_TRUE(actual.has_colors());
    for (std::size_t i = 0; i < match.size(); ++i) {
      EXPECT_LT((actual.colors[i] - expected.colors[match[i]]).norm(), 1e-5f) << "colour " << i;
    }
  }
}

}  // namespace forensim::test
