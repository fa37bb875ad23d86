#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/primitives.hpp"
#include "texture/uv_bake.hpp"

using namespace forensim;

namespace {

/// Square of side `side` mm in the z = 0 plane with identity UVs (u = x / side, v = y / side).
TriMesh make_square(double side) {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(side, 0, 0), Vec3(side, side, 0), Vec3(0, side, 0)};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  mesh.triangle_uvs = mesh.triangles;
  return mesh;
}

/// 20 mm box with each face projected onto its own cell of a 3 x 2 grid, keeping the orientation
/// (counter-clockwise faces get counter-clockwise UVs), half a cell of margin around each face.
TriMesh make_box_with_atlas(std::vector<int>& face_of_triangle) {
  TriMesh box = make_box_mesh(Vec3(-10, -10, -10), Vec3(10, 10, 10), 2);
  box.normals.clear();  // welded corners would average the faces' normals
  const std::vector<Vec3> normals = face_normals(box);
  face_of_triangle.clear();
  for (std::size_t t = 0; t < box.triangles.size(); ++t) {
    const Vec3& n = normals[t];
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    const int face = 2 * axis + (n[axis] > 0 ? 1 : 0);
    face_of_triangle.push_back(face);
    // In-plane axes (a, b) with a x b = n, so projected triangles stay counter-clockwise.
    const Vec3 a = Vec3::Unit((axis + 1) % 3) * (n[axis] > 0 ? 1.0 : -1.0);
    const Vec3 bb = n.cross(a);  // a x (n x a) = n
    const Vec2 cell((face % 3) / 3.0, (face / 3) / 2.0);
    Tri corners{};
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = box.positions[static_cast<std::size_t>(box.triangles[t][static_cast<std::size_t>(k)])];
      const Vec2 local((p.dot(a) + 10.0) / 20.0, (p.dot(bb) + 10.0) / 20.0);  // [0,1]^2 on the face
      corners[static_cast<std::size_t>(k)] = static_cast<Index>(box.uvs.size());
      box.uvs.push_back(cell + Vec2(0.25 / 3.0 + local.x() * 0.5 / 3.0, 0.25 / 2.0 + local.y() * 0.5 / 2.0));
    }
    box.triangle_uvs.push_back(corners);
  }
  return box;
}

void expect_orthonormal_frame(const UvTexel& t) {
  EXPECT_NEAR(t.normal.norm(), 1.0, 1e-9);
  EXPECT_NEAR(t.tangent.norm(), 1.0, 1e-9);
  EXPECT_NEAR(t.bitangent.norm(), 1.0, 1e-9);
  EXPECT_NEAR(t.normal.dot(t.tangent), 0.0, 1e-9);
  EXPECT_NEAR(t.normal.dot(t.bitangent), 0.0, 1e-9);
  EXPECT_NEAR(t.tangent.dot(t.bitangent), 0.0, 1e-9);
}

}  // namespace

TEST(UvBake, SquareWithIdentityUvsBakesTexelCentres) {
  const double side = 10.0;
  const int w = 32, h = 24;
  const UvRaster raster = rasterize_uv(make_square(side), w, h);
  ASSERT_EQ(raster.texels.size(), static_cast<std::size_t>(w * h));  // every centre is inside the square
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ASSERT_GE(raster.at(x, y), 0);
      const UvTexel& t = raster.texels[static_cast<std::size_t>(raster.at(x, y))];
      EXPECT_EQ(t.x, x);
      EXPECT_EQ(t.y, y);
      const Vec3 expected((x + 0.5) / w * side, (1.0 - (y + 0.5) / h) * side, 0.0);  // v up, rows down
      EXPECT_NEAR((t.position - expected).norm(), 0.0, 1e-12);
      EXPECT_NEAR((t.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
      EXPECT_NEAR((t.tangent - Vec3::UnitX()).norm(), 0.0, 1e-12);
      EXPECT_NEAR((t.bitangent - Vec3::UnitY()).norm(), 0.0, 1e-12);
      EXPECT_NEAR(t.barycentric.sum(), 1.0, 1e-12);
    }
  }
}

TEST(UvBake, BoxAtlasBakesFaceNormalsAndPositionsOnTheFaces) {
  std::vector<int> face;
  const TriMesh box = make_box_with_atlas(face);
  const std::vector<Vec3> normals = face_normals(box);
  const UvRaster raster = rasterize_uv(box, 96, 64);
  ASSERT_GT(raster.texels.size(), 6u * 100u);
  for (const UvTexel& t : raster.texels) {
    const Vec3& n = normals[static_cast<std::size_t>(t.triangle)];
    EXPECT_NEAR((t.normal - n).norm(), 0.0, 1e-12);  // no vertex normals: the face normal
    EXPECT_NEAR(t.position.dot(n), 10.0, 1e-9);      // on the face plane
    expect_orthonormal_frame(t);
    // uv_at inverts the raster: the texel's triangle and barycentrics give back its centre.
    const Vec2 px = uv_to_pixel(uv_at(box, t.triangle, t.barycentric), 96, 64);
    EXPECT_NEAR(px.x(), t.x + 0.5, 1e-9);
    EXPECT_NEAR(px.y(), t.y + 0.5, 1e-9);
  }
  // The tangent points along +u: a texel step to the right moves the surface point along it.
  int checked = 0;
  for (const UvTexel& t : raster.texels) {
    if (t.x + 1 >= 96 || raster.at(t.x + 1, t.y) < 0) continue;
    const UvTexel& r = raster.texels[static_cast<std::size_t>(raster.at(t.x + 1, t.y))];
    if (face[static_cast<std::size_t>(r.triangle)] != face[static_cast<std::size_t>(t.triangle)]) continue;
    const Vec3 step = r.position - t.position;
    EXPECT_NEAR(step.normalized().dot(t.tangent), 1.0, 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 500);
  // Coverage: six faces of a quarter of their cell each.
  EXPECT_NEAR(static_cast<double>(raster.texels.size()) / (96.0 * 64.0), 0.25, 0.02);
}

TEST(UvBake, InterpolatedFramesAreOrthonormalAndHandleMirroredUvs) {
  TriMesh sphere = make_icosphere(Vec3(0, 0, 0), 20.0, 2);
  compute_normals(sphere);
  // Planar projection along z: front triangles counter-clockwise, back ones mirrored.
  for (const Vec3& p : sphere.positions) sphere.uvs.push_back(Vec2(p.x() / 40.0 + 0.5, p.y() / 40.0 + 0.5));
  sphere.triangle_uvs = sphere.triangles;
  const UvRaster raster = rasterize_uv(sphere, 64, 64);
  ASSERT_GT(raster.texels.size(), 2000u);
  for (const UvTexel& t : raster.texels) {
    expect_orthonormal_frame(t);
    Vec3 dp_du, dp_dv;
    triangle_tangents(sphere, t.triangle, dp_du, dp_dv);
    EXPECT_GE(t.bitangent.dot(dp_dv), 0.0);  // follows +v on both sides
    EXPECT_GE(t.tangent.dot(dp_du), 0.0);
  }
}

TEST(UvBake, BakeIsDeterministicAndDilatesIntoTheGutter) {
  std::vector<int> face;
  const TriMesh box = make_box_with_atlas(face);
  const UvRaster raster = rasterize_uv(box, 60, 40);
  const auto shader = [](const UvTexel& t) {
    return Vec4f(static_cast<float>(0.5 + 0.02 * t.position.x()), static_cast<float>(0.5 + 0.02 * t.position.y()),
                 static_cast<float>(0.5 + 0.02 * t.position.z()), 1.0f);
  };
  set_thread_count(1);
  const Image one = bake(raster, 4, shader, 2);
  set_thread_count(0);
  const Image all = bake(raster, 4, shader, 2);
  EXPECT_EQ(one.data(), all.data());
  EXPECT_EQ(coverage(raster).size(), 60u * 40u);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 60; ++x) {
      // Chebyshev distance to the nearest covered texel.
      int d = 99;
      for (const UvTexel& t : raster.texels) d = std::min(d, std::max(std::abs(t.x - x), std::abs(t.y - y)));
      const float alpha = all.at(x, y, 3);
      if (d == 0) {
        const UvTexel& t = raster.texels[static_cast<std::size_t>(raster.at(x, y))];
        EXPECT_FLOAT_EQ(all.at(x, y, 0), shader(t).x());
      }
      // Covered or dilated within two rings; background beyond.
      EXPECT_EQ(alpha, d <= 2 ? 1.0f : 0.0f) << x << " " << y;
    }
  }
}

TEST(UvBake, PaddingTexelsExtrapolateOnTheTrianglePlane) {
  TriMesh square = make_square(10.0);
  square.uvs = {Vec2(0.25, 0.25), Vec2(0.75, 0.25), Vec2(0.75, 0.75), Vec2(0.25, 0.75)};  // 20 mm per UV unit
  const int n = 32;
  const UvRaster plain = rasterize_uv(square, n, n);
  const UvRaster padded = rasterize_uv(square, n, n, 2);
  EXPECT_EQ(plain.texels.size(), 16u * 16u);
  EXPECT_EQ(padded.texels.size(), 20u * 20u);  // two rings on each side (corners through diagonal neighbours)
  for (const UvTexel& t : padded.texels) {
    const double u = (t.x + 0.5) / n, v = 1.0 - (t.y + 0.5) / n;
    const Vec3 expected((u - 0.25) * 20.0, (v - 0.25) * 20.0, 0.0);
    EXPECT_NEAR((t.position - expected).norm(), 0.0, 1e-9);
    EXPECT_EQ(t.inside, plain.at(t.x, t.y) >= 0);
    EXPECT_NEAR((t.normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  }
  EXPECT_THROW(rasterize_uv(square, n, n, -1), InputError);
}

TEST(UvBake, RejectsMeshesWithoutUvsAndBadSizes) {
  TriMesh mesh = make_square(1.0);
  EXPECT_THROW(rasterize_uv(mesh, 0, 8), InputError);
  EXPECT_THROW(rasterize_uv(mesh, 8, 20000), InputError);
  mesh.uvs.clear();
  mesh.triangle_uvs.clear();
  EXPECT_THROW(rasterize_uv(mesh, 8, 8), InputError);
}
