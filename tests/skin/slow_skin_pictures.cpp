// Pictures of the skin shader on the forearm-uv phantom: the livor mortis start state (the arm lying on its
// thumb side on a table) and drying stages with a drying front from the fingers, rendered with
// vertex colours into a sheet, plus the generated look-up texture and a baked colour map. Written to the
// scratch folder (and docs/images with FORENSIM_WRITE_DOC_IMAGES=1). Checks what the pictures must show.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "image/png_io.hpp"
#include "phantoms/forearm_uv.hpp"
#include "phantoms/skin_maps.hpp"
#include "render/renderer.hpp"
#include "render/sheet.hpp"
#include "skin/skin_map_baker.hpp"
#include "skin/skin_shader.hpp"
#include "support/test_support.hpp"

using namespace forensim;

namespace {
double luminance(const Vec4f& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}
}  // namespace

TEST(SkinPictures, ForearmLivorAndDryingStages) {
  const ForearmUvModel model = make_forearm_uv();
  TriMesh arm = model.mesh;
  const std::size_t n = arm.vertex_count();
  const Vec3 gravity(0, -1, 0);  // lying on the thumb side, which faces the camera of the front view
  LivorSettings livor_settings;
  livor_settings.gravity = gravity;
  const LivorState livor = settle_livor(arm, contact_near_plane(arm, gravity, 4.0), livor_settings);

  // Epidermis and melanin from the phantom's procedural skin (melanin there is about 0.1 to 1: scaled to a
  // melanosome fraction of a light skin).
  const SkinTexture texture(1, 1.0);
  std::vector<Vec3> epidermis(n);
  std::vector<double> melanin(n);
  for (std::size_t i = 0; i < n; ++i) {
    const SkinSample s = texture.evaluate(arm.positions[i], arm.normals[i]);
    epidermis[i] = s.epidermis.cwiseMax(0.0).cwiseMin(1.0);
    melanin[i] = 0.03 * s.melanin;
  }
  const SkinLayers layers = make_skin_layers(epidermis, melanin);
  const SkinShader shader;

  double x_min = arm.positions[0][0], x_max = x_min;
  for (const Vec3& p : arm.positions) {
    x_min = std::min(x_min, p[0]);
    x_max = std::max(x_max, p[0]);
  }
  const std::vector<std::pair<double, std::string>> stages = {
      {0.0, "start (livor)"}, {0.5, "day 10"}, {1.0, "day 25"}, {1.6, "day 60"}};
  std::vector<SheetCell> cells;
  std::vector<double> mean_luminance;
  std::vector<Vec4f> colours;
  for (const auto& [progress, caption] : stages) {
    std::vector<double> moisture(n);
    for (std::size_t i = 0; i < n; ++i) {  // drying front from the fingertips (x distal)
      const double distal = (arm.positions[i][0] - x_min) / (x_max - x_min);
      moisture[i] = std::clamp(1.0 - progress * (0.4 + 0.8 * distal), 0.0, 1.0);
    }
    shader.shade(layers, livor, moisture, 24.0 * 10.0 * progress, colours);
    double sum = 0;
    for (const Vec4f& c : colours) sum += luminance(c);
    mean_luminance.push_back(sum / static_cast<double>(n));
    arm.colors = colours;
    SurfaceMaterial material = SurfaceMaterial::skin();
    material.colour_source = ColourSource::vertex_colours;
    material.base_colour = Vec3f(1, 1, 1);
    Scene scene;
    scene.add(arm, material);
    scene.frame(ViewName::front, 2.0);
    RenderSettings settings;
    settings.width = 480;
    settings.height = 240;
    settings.samples_per_pixel = 4;
    settings.exposure_stops = -0.7;  // the skin's albedo as it is, not lifted by the tone curve
    cells.push_back({Renderer(scene).render(settings), caption});
    if (progress == 0.0) {
      // Livor against the same skin with the blood spread evenly: red falls in the lowest tenth of the height
      // (outside the contact areas), rises at the top, and the contact areas stay pale.
      LivorState even = livor;
      std::fill(even.vertex_hemoglobin.begin(), even.vertex_hemoglobin.end(), LivorSettings{}.blood_fill);
      std::fill(even.vertex_capacity.begin(), even.vertex_capacity.end(), 1.0);
      const std::vector<Vec4f> reference = shader.shade(layers, even, moisture, 0.0);
      const double range = livor.height_max_mm - livor.height_min_mm;
      double low = 0, top = 0, contact = 0;
      int n_low = 0, n_top = 0, n_contact = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double h = (-arm.positions[i].dot(gravity) - livor.height_min_mm) / range;
        const double ratio = colours[i][0] / reference[i][0];
        if (livor.vertex_contact[i]) {
          contact += ratio;
          ++n_contact;
        } else if (h < 0.1) {
          low += ratio;
          ++n_low;
        } else if (h > 0.9) {
          top += ratio;
          ++n_top;
        }
      }
      ASSERT_GT(n_low, 10);
      ASSERT_GT(n_top, 10);
      ASSERT_GT(n_contact, 3);
      EXPECT_LT(low / n_low, 0.95);
      EXPECT_GT(top / n_top, 1.02);
      EXPECT_GT(contact / n_contact, 1.02);
    }
  }
  for (std::size_t k = 1; k < mean_luminance.size(); ++k) EXPECT_LT(mean_luminance[k], mean_luminance[k - 1]);

  const Image sheet = make_sheet(cells, 2, "forearm: livor mortis, then drying from the fingers");
  const SkinMapBaker baker(arm, 512);
  const Image map = baker.bake_colours(colours);
  EXPECT_EQ(map.width(), 512);
  const auto dir = test::scratch_dir("skin_pictures");
  write_png(dir / "forearm_stages.png", sheet);
  write_png(dir / "forearm_dried_colour.png", map);
  write_dermis_lut(shader.lut(), dir / "dermis_lut.png", 4);
  write_dermis_lut(shader.lut(), dir / "dermis_lut.exr");
  std::cout << "pictures in " << dir << "\n";
  const char* docs = std::getenv("FORENSIM_WRITE_DOC_IMAGES");
  if (docs && std::string(docs) == "1") {
    const auto images = test::tests_dir().parent_path() / "docs/images";
    write_png(images / "skin_forearm_stages.png", sheet);
    write_dermis_lut(shader.lut(), images / "skin_dermis_lut.png", 4);
  }
}
