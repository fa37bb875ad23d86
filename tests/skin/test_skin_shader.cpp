// The mummification skin shader per vertex: hydrated skin at time 0 is the livor mortis start state, drying
// darkens and browns monotonically, time deoxygenates, results do not depend on the thread count.

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/primitives.hpp"
#include "skin/skin_shader.hpp"

using namespace forensim;

namespace {

double luminance(const Vec3& c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

struct Fixture {
  TriMesh skin = make_icosphere(Vec3::Zero(), 50.0, 4);
  LivorState livor = settle_livor(skin, contact_near_plane(skin, Vec3(0, 0, -1), 4.0));
  SkinLayers layers = [this] {
    std::vector<Vec3> epidermis(skin.vertex_count());
    std::vector<double> melanin(skin.vertex_count());
    for (std::size_t i = 0; i < epidermis.size(); ++i) {  // a varied epidermis map
      const Vec3& p = skin.positions[i];
      epidermis[i] = Vec3(0.78, 0.64, 0.54) + 0.04 * Vec3(std::sin(p[0] / 9), std::cos(p[1] / 7), std::sin(p[2] / 5));
      melanin[i] = 0.02 + 0.02 * (0.5 + 0.5 * std::sin(p[0] / 13 + p[1] / 11));
    }
    return make_skin_layers(epidermis, melanin);
  }();
};

Vec3 shade_one(const SkinShader& shader, double saturation, double oxygen, double moisture, double hours) {
  const SkinLayers layers = uniform_skin_layers(1);
  return shader.shade_vertex(layers.vertex_epidermis[0], layers.vertex_absorption_hydrated[0],
                             layers.vertex_absorption_dehydrated[0], saturation, 1.0, oxygen, moisture, hours);
}

}  // namespace

TEST(SkinShader, HydratedSkinAtTimeZeroIsTheLivorStartState) {
  const Fixture f;
  const SkinShader shader;
  const std::vector<double> hydrated(f.skin.vertex_count(), 1.0);
  const std::vector<Vec4f> shaded = shader.shade(f.layers, f.livor, hydrated, 0.0);
  const std::vector<Vec4f> livor = livor_colours(f.layers, f.livor);
  ASSERT_EQ(shaded.size(), livor.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < shaded.size(); ++i) worst = std::max(worst, double((shaded[i] - livor[i]).norm()));
  EXPECT_LT(worst, 2e-3);  // the look-up texture's bilinear interpolation error
  // The start state shows livor: the lowest non-contact parts are darker and bluer than the top.
  std::size_t top = 0, low = 0;
  for (std::size_t i = 0; i < f.skin.vertex_count(); ++i) {
    if (f.skin.positions[i][2] > f.skin.positions[top][2]) top = i;
    if (!f.livor.vertex_contact[i] &&
        (f.livor.vertex_contact[low] || f.skin.positions[i][2] < f.skin.positions[low][2]))
      low = i;
  }
  const Vec4f pale = livor[top], livid = livor[low];
  EXPECT_LT(livid[0] + livid[1] + livid[2], 0.92f * (pale[0] + pale[1] + pale[2]));
  EXPECT_GT(livid[2] / livid[0], pale[2] / pale[0]);  // bluish purple against the pale top
}

TEST(SkinShader, DehydrationDarkensMonotonicallyAndBrowns) {
  const SkinShader shader;
  for (double s : {0.05, 0.35, 0.7, 1.0}) {
    Vec3 previous = shade_one(shader, s, 0.15, 1.0, 240.0);
    const Vec3 wet = previous;
    for (int k = 39; k >= 0; --k) {
      const double m = k / 40.0;
      const Vec3 c = shade_one(shader, s, 0.15, m, 240.0);
      EXPECT_LT(luminance(c), luminance(previous)) << "s " << s << " m " << m;
      previous = c;
    }
    // Dried skin is brown (red > green > blue), much darker than fresh and far less blue.
    EXPECT_GT(previous[0], previous[1]);
    EXPECT_GT(previous[1], 1.1 * previous[2]);
    EXPECT_LT(luminance(previous), 0.6 * luminance(wet)) << s;
    EXPECT_LT(previous[2] / previous[0], 0.8 * wet[2] / wet[0]) << s;
  }
}

TEST(SkinShader, WithoutTheGreenStageDryingBrownsMonotonically) {
  // The green stage is a detour of the hue by design; without biliverdin, blue over red falls at every step
  // wherever there is blood (blanched skin first shows a little more of its bloodless dermis in blue as the
  // weights of eq. 39 move to the dermis).
  SkinShadingSettings settings;
  settings.lut.heme_to_biliverdin = 0.0;
  const SkinShader shader(settings);
  for (double s : {0.35, 0.7, 1.0}) {
    Vec3 previous = shade_one(shader, s, 0.15, 1.0, 240.0);
    for (int k = 39; k >= 0; --k) {
      const double m = k / 40.0;
      const Vec3 c = shade_one(shader, s, 0.15, m, 240.0);
      EXPECT_LT(c[2] / c[0], previous[2] / previous[0]) << "s " << s << " m " << m;
      EXPECT_LT(luminance(c), luminance(previous)) << "s " << s << " m " << m;
      previous = c;
    }
  }
}

TEST(SkinShader, TimeDeoxygenatesTheBlood) {
  const SkinShader shader;
  EXPECT_DOUBLE_EQ(shader.oxygen_at(0.8, 0.0), 0.8);
  EXPECT_NEAR(shader.oxygen_at(0.8, shader.settings().oxygen_decay_hours), 0.8 / std::exp(1.0), 1e-12);
  const Vec3 fresh = shade_one(shader, 1.0, 1.0, 1.0, 0.0), later = shade_one(shader, 1.0, 1.0, 1.0, 72.0);
  EXPECT_LT(later[0], fresh[0] - 0.02);  // oxygenated red turns to the darker deoxygenated purple
  EXPECT_LT(luminance(later), luminance(fresh));
}

TEST(SkinShader, GreenStageLiesBetweenHydratedAndDried) {
  const SkinShader shader;
  const double m = green_stage_moisture(shader);
  EXPECT_GT(m, 0.1);
  EXPECT_LT(m, 0.9);
  const Vec3 green = shade_one(shader, 1.0, 0.0, m, 240.0);
  const Vec3 wet = shade_one(shader, 1.0, 0.0, 1.0, 240.0), dry = shade_one(shader, 1.0, 0.0, 0.0, 240.0);
  EXPECT_GT(green[1] / green[0], wet[1] / wet[0]);
  EXPECT_GT(green[1] / green[0], dry[1] / dry[0]);
}

TEST(SkinShader, SameColoursAtAnyThreadCount) {
  const Fixture f;
  const SkinShader shader;
  std::vector<double> moisture(f.skin.vertex_count());
  for (std::size_t i = 0; i < moisture.size(); ++i) moisture[i] = 0.5 + 0.5 * std::sin(0.1 * static_cast<double>(i));
  set_thread_count(1);
  const std::vector<Vec4f> one = shader.shade(f.layers, f.livor, moisture, 30.0);
  set_thread_count(2);
  const std::vector<Vec4f> two = shader.shade(f.layers, f.livor, moisture, 30.0);
  set_thread_count(0);
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) ASSERT_EQ(one[i], two[i]) << i;
}

TEST(SkinShader, RejectsBadInput) {
  const Fixture f;
  const SkinShader shader;
  EXPECT_THROW(shader.shade(f.layers, f.livor, std::vector<double>(5, 1.0), 0.0), InputError);
  EXPECT_THROW(shader.shade(f.layers, f.livor, std::vector<double>(f.skin.vertex_count(), 1.0), -1.0), InputError);
  SkinShadingSettings s;
  s.oxygen_decay_hours = 0.0;
  EXPECT_THROW(SkinShader{s}, InputError);
  EXPECT_THROW(make_skin_layers({Vec3(0.5, 0.5, 0.5)}, {1.5}), InputError);
  EXPECT_THROW(make_skin_layers({Vec3(0.5, 0.5, 0.5)}, {}), InputError);
}
