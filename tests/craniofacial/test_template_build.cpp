// A template built from a head: from the template's own head it is the template again; from a moved and scaled
// copy it is the template at that size (the warp reproduces a similarity exactly and the skin conforms); a head
// mesh's texture comes back on the atlas.
#include "craniofacial/template_build.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "craniofacial/template_landmark_detection.hpp"
#include "image/png_io.hpp"
#include "spatial/closest_point.hpp"
#include "template_head_fixture.hpp"
#include "texture/uv_bake.hpp"

using namespace forensim;
using forensim::test::coarse_template_head;

namespace {

struct Similar {
  double scale = 1.0;
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 apply(const Vec3& p) const { return scale * (rotation * p) + translation; }
  TriMesh apply(TriMesh m) const {
    for (Vec3& p : m.positions) p = apply(p);
    m.normals.clear();
    return m;
  }
};

LandmarkSet moved_skull_landmarks(const TemplateHead& head, const Similar& s) {
  LandmarkSet out("skull");
  const LandmarkSet on_template = template_skull_landmarks(head);
  for (const Landmark& l : on_template.landmarks()) {
    out.add({l.name, s.apply(l.position_mm), LandmarkSource::imported, 1.0});
  }
  return out;
}

double max_distance_ratio_error(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double ratio) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); i += 97) {
    for (std::size_t j = i + 41; j < a.size(); j += 1013) {
      worst = std::max(worst, std::abs((b[i] - b[j]).norm() - ratio * (a[i] - a[j]).norm()));
    }
  }
  return worst;
}

}  // namespace

TEST(TemplateBuild, FromTheTemplatesOwnHeadIsTheTemplate) {
  const TemplateHead& base = coarse_template_head();
  TemplateBuildInput input;
  input.source = "the template itself";
  input.skin = base.skin;
  input.skull = base.skull;
  input.skull_landmarks = template_skull_landmarks(base);
  for (const TemplateLandmarkPair& p : base.landmarks) {
    input.skin_landmarks.add({p.skin_name, p.skin, LandmarkSource::imported, 1.0});
  }
  const TemplateBuild built = build_template_head(base, input);
  ASSERT_EQ(built.head.skin.positions.size(), base.skin.positions.size());
  double worst = 0.0;
  for (std::size_t v = 0; v < base.skin.positions.size(); ++v) {
    worst = std::max(worst, (built.head.skin.positions[v] - base.skin.positions[v]).norm());
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(built.head.skin.triangles, base.skin.triangles);
  EXPECT_EQ(built.head.triangle_chart, base.triangle_chart);
  EXPECT_EQ(built.report.flipped_triangles, 0u);
  EXPECT_GT(built.report.vertices_conformed, base.skin.positions.size() * 9 / 10);
  for (std::size_t i = 0; i < base.skin_landmarks.size(); ++i) {
    EXPECT_LT((built.head.skin_landmarks[i].position - base.skin_landmarks[i].position).norm(), 1e-6);
  }
  // Muscle grids on the skin: where the template's grid points lie closest to it.
  const ClosestPointQuery base_skin(base.skin);
  for (std::size_t m = 0; m < base.muscles.size(); ++m) {
    for (std::size_t k = 0; k < base.muscles[m].grid.size(); ++k) {
      EXPECT_LT((built.head.muscles[m].grid[k] - base_skin.query(base.muscles[m].grid[k])->point).norm(), 1e-6)
          << base.muscles[m].name;
    }
  }
  // Each pair measured on the skull: its skin point on the skin, its depth the distance.
  const ClosestPointQuery skin(built.head.skin);
  for (const TemplateLandmarkPair& p : built.head.landmarks) {
    EXPECT_LT(skin.query(p.skin)->distance, 1e-6) << p.skin_name;
    EXPECT_NEAR(p.depth_mm, (p.skin - p.skull).norm(), 1e-9) << p.skin_name;
    EXPECT_NEAR(p.skull_normal.norm(), 1.0, 1e-12);
  }
  EXPECT_EQ(built.report.pairs_from_skin.size(), base.landmarks.size());
}

TEST(TemplateBuild, FromASkullAndItsLandmarksMeasuresTheSkinAlongTheSkullNormals) {
  const TemplateHead& base = coarse_template_head();
  TemplateBuildInput input;
  input.skin = base.skin;
  input.skull = base.skull;
  input.skull_landmarks = template_skull_landmarks(base);
  const TemplateBuild built = build_template_head(base, input);
  EXPECT_EQ(built.report.pairs_from_skull.size(), base.landmarks.size());
  EXPECT_TRUE(built.report.pairs_left.empty());
  // The skin points found along the patch normals differ a little from the template's (its normals are the
  // phantom's gradient): the warped skin slides on itself and conforms back onto the same surface.
  const ClosestPointQuery base_skin(base.skin);
  double worst = 0.0;
  for (std::size_t v = 0; v < built.head.skin.positions.size(); ++v) {
    worst = std::max(worst, base_skin.query(built.head.skin.positions[v])->distance);
  }
  std::printf("skull-measured build: %zu conformed, %zu warped, mean move %.3f mm, farthest off the skin %.3f mm\n",
              built.report.vertices_conformed, built.report.vertices_warped, built.report.mean_conform_mm, worst);
  EXPECT_GT(built.report.vertices_conformed, built.head.skin.positions.size() * 99 / 100);
  EXPECT_LT(worst, 1e-6);
  // Depths along the patch normals: most as the template's own (along its phantom normals); a few sites where the
  // skin folds (subnasale under the nose, the lower lip) meet it elsewhere along a slightly turned normal.
  std::size_t close = 0;
  for (std::size_t i = 0; i < base.landmarks.size(); ++i) {
    const TemplateLandmarkPair& p = built.head.landmarks[i];
    EXPECT_LT(base_skin.query(p.skin)->distance, 1e-6) << p.skin_name;
    EXPECT_NEAR(p.depth_mm, (p.skin - p.skull).norm(), 1e-9) << p.skin_name;
    if (std::abs(p.depth_mm - base.landmarks[i].depth_mm) <= 0.25 * base.landmarks[i].depth_mm + 1.0) ++close;
  }
  EXPECT_GE(close, base.landmarks.size() * 9 / 10);
}

TEST(TemplateBuild, FromAMovedLargerCopyIsTheTemplateAtThatSize) {
  const TemplateHead& base = coarse_template_head();
  Similar s;
  s.scale = 1.08;
  s.rotation = Eigen::AngleAxisd(0.5, Vec3(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  s.translation = Vec3(40.0, -25.0, 300.0);
  TemplateBuildInput input;
  input.skin = s.apply(base.skin);
  input.skull = s.apply(base.skull);
  input.skull_landmarks = moved_skull_landmarks(base, s);
  for (const TemplateLandmarkPair& p : base.landmarks) {
    input.skin_landmarks.add({p.skin_name, s.apply(p.skin), LandmarkSource::imported, 1.0});
  }
  const TemplateBuild built = build_template_head(base, input);
  // Distances grow by the scale: the warp of a similarity is that similarity (eq. 1's affine part), the rigid
  // placement keeps the size, and the skin conforms onto the copy where it already lies.
  EXPECT_LT(max_distance_ratio_error(base.skin.positions, built.head.skin.positions, s.scale), 1e-5);
  EXPECT_LT(max_distance_ratio_error(base.skull.positions, built.head.skull.positions, s.scale), 1e-6);
  EXPECT_EQ(built.report.flipped_triangles, 0u);
  // The skin found the copy's (placed in the template's frame) along its normals.
  EXPECT_GT(built.report.vertices_conformed, built.head.skin.positions.size() * 99 / 100);
  EXPECT_LT(built.report.mean_conform_mm, 1e-6);
  // Placed in the template's frame: the centroid of the skull landmarks lands on the template's (scaled about it).
  Vec3 cb = Vec3::Zero(), cn = Vec3::Zero();
  for (std::size_t i = 0; i < base.landmarks.size(); ++i) {
    cb += base.landmarks[i].skull;
    cn += built.head.landmarks[i].skull;
  }
  EXPECT_LT((cb - cn).norm() / static_cast<double>(base.landmarks.size()), 2.0);
}

TEST(TemplateBuild, FromSkinLandmarksAndATextureBakesTheTextureOntoTheAtlas) {
  const TemplateHead& base = coarse_template_head();
  ASSERT_TRUE(base.skin.has_uvs());
  Similar s;
  s.scale = 0.95;
  s.translation = Vec3(5.0, 0.0, -3.0);
  TemplateBuildInput input;
  input.skin = s.apply(base.skin);
  for (const TemplateLandmarkPair& p : base.landmarks) {
    input.skin_landmarks.add({p.skin_name, s.apply(p.skin), LandmarkSource::imported, 1.0});
  }
  // A texture that shows its own UVs: red = u, green = v.
  const int n = 256;
  input.texture = Image(n, n, 3);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      input.texture.at(x, y, 0) = (x + 0.5f) / n;
      input.texture.at(x, y, 1) = 1.0f - (y + 0.5f) / n;
    }
  }
  TemplateBuildOptions options;
  options.texture_size = 128;
  const TemplateBuild built = build_template_head(base, input, options);
  EXPECT_TRUE(built.report.texture_baked);
  EXPECT_EQ(built.report.pairs_from_skin.size(), base.landmarks.size());
  // No skull given: the template's sits under the skin at the template's own depths.
  EXPECT_TRUE(built.report.skull_at_template_depths);
  std::size_t same_depth = 0;
  for (std::size_t i = 0; i < base.landmarks.size(); ++i) {
    const double d = base.landmarks[i].depth_mm;
    if (std::abs(built.head.landmarks[i].depth_mm - d) < 0.1 * d + 1.0) ++same_depth;
  }
  EXPECT_GE(same_depth, base.landmarks.size() * 8 / 10);
  const Image baked = decode_png(built.head.texture_png, "baked texture");
  ASSERT_EQ(baked.width(), 128);
  const UvRaster raster = rasterize_uv(built.head.skin, 128, 128);
  double sum = 0.0;
  std::size_t count = 0;
  for (const UvTexel& t : raster.texels) {
    const double u = (t.x + 0.5) / 128.0, v = 1.0 - (t.y + 0.5) / 128.0;
    sum += std::abs(baked.at(t.x, t.y, 0) - u) + std::abs(baked.at(t.x, t.y, 1) - v);
    ++count;
  }
  ASSERT_GT(count, 1000u);
  // Linear values after an 8-bit sRGB round trip: about 1/255 where a texel sees its own UV.
  EXPECT_LT(sum / (2.0 * static_cast<double>(count)), 0.01);
}

TEST(TemplateBuild, SkinLandmarksByRegistrationFindTheTemplatesOnAMovedCopy) {
  const TemplateHead& base = coarse_template_head();
  Similar s;
  s.scale = 1.1;
  s.rotation = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
  s.translation = Vec3(10.0, 20.0, -5.0);
  const TriMesh head = s.apply(base.skin);
  double rms = -1.0;
  const LandmarkSet found = skin_landmarks_by_registration(base, head, &rms);
  EXPECT_LT(rms, 0.5);
  ASSERT_EQ(found.size(), base.landmarks.size() + base.skin_landmarks.size());
  std::vector<double> errors;
  for (const TemplateLandmarkPair& p : base.landmarks)
    errors.push_back((found.at(p.skin_name).position_mm - s.apply(p.skin)).norm());
  std::sort(errors.begin(), errors.end());
  std::printf("skin landmarks by registration: median %.2f mm, largest %.2f mm\n", errors[errors.size() / 2],
              errors.back());
  EXPECT_LT(errors[errors.size() / 2], 1.0);
  EXPECT_LT(errors.back(), 4.0);
}

TEST(TemplateBuild, RefusesTooFewLandmarksAndATextureWithoutUvs) {
  const TemplateHead& base = coarse_template_head();
  TemplateBuildInput input;
  input.source = "scan.obj";
  input.skin = base.skin;
  input.skin_landmarks.add({"se'", base.landmarks[0].skin, LandmarkSource::imported, 1.0});
  try {
    build_template_head(base, input);
    FAIL() << "built from one landmark";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scan.obj"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("at least 4"), std::string::npos);
  }
  input.skin.uvs.clear();
  input.skin.triangle_uvs.clear();
  input.texture = Image(4, 4, 3);
  EXPECT_THROW(build_template_head(base, input), InputError);
  TemplateBuildInput empty;
  EXPECT_THROW(build_template_head(base, empty), InputError);
}
