#include "craniofacial/face_guides_job.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace forensim {
namespace {

constexpr double kBig = 1e6;  // mm: any guide coordinate beyond a kilometre is a mistake

std::optional<double> optional_number(const JobNode& node, const std::string& key) {
  if (!node.has(key)) return std::nullopt;
  return node.get_number(key, 0.0, -kBig, kBig);
}

std::optional<Vec3> optional_vector(const JobNode& node, const std::string& key) {
  if (!node.has(key)) return std::nullopt;
  const auto values = node.require<std::vector<double>>(key);
  if (values.size() != 3) node.fail(key, "expected [x, y, z], got " + std::to_string(values.size()) + " numbers");
  for (double v : values)
    if (!std::isfinite(v) || std::abs(v) > kBig) node.fail(key, "coordinates must be finite numbers (mm)");
  return Vec3(values[0], values[1], values[2]);
}

nlohmann::json vector_json(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

}  // namespace

FaceGuides read_face_guides(const JobNode& node) {
  FaceGuides g;
  if (auto v = optional_vector(node, "lateral")) g.lateral = *v;
  if (auto v = optional_vector(node, "up")) g.up = *v;
  g.nasal_aperture_left_mm = optional_number(node, "nasal_aperture_left_mm");
  g.nasal_aperture_right_mm = optional_number(node, "nasal_aperture_right_mm");
  g.alar_offset_mm = node.get_number("alar_offset_mm", g.alar_offset_mm, 0.0, 50.0);
  g.nasal_spine_base = optional_vector(node, "nasal_spine_base");
  g.nasal_spine_tip = optional_vector(node, "nasal_spine_tip");
  g.krogman_factor = node.get_number("krogman_factor", g.krogman_factor, 0.0, 20.0);
  g.mouth_corner_left_mm = optional_number(node, "mouth_corner_left_mm");
  g.mouth_corner_right_mm = optional_number(node, "mouth_corner_right_mm");
  g.upper_lip_border_mm = optional_number(node, "upper_lip_border_mm");
  g.lower_lip_border_mm = optional_number(node, "lower_lip_border_mm");
  g.lip_parting_mm = optional_number(node, "lip_parting_mm");
  return g;
}

bool any_guide(const FaceGuides& g) {
  return g.nasal_aperture_left_mm || g.nasal_aperture_right_mm || g.nasal_spine_base || g.nasal_spine_tip ||
         g.mouth_corner_left_mm || g.mouth_corner_right_mm || g.upper_lip_border_mm || g.lower_lip_border_mm ||
         g.lip_parting_mm;
}

nlohmann::json face_guides_json(const FaceGuides& g) {
  nlohmann::json j = {{"lateral", vector_json(g.lateral)},
                      {"up", vector_json(g.up)},
                      {"alar_offset_mm", g.alar_offset_mm},
                      {"krogman_factor", g.krogman_factor}};
  auto number = [&j](const char* key, const std::optional<double>& v) {
    if (v) j[key] = *v;
  };
  number("nasal_aperture_left_mm", g.nasal_aperture_left_mm);
  number("nasal_aperture_right_mm", g.nasal_aperture_right_mm);
  number("mouth_corner_left_mm", g.mouth_corner_left_mm);
  number("mouth_corner_right_mm", g.mouth_corner_right_mm);
  number("upper_lip_border_mm", g.upper_lip_border_mm);
  number("lower_lip_border_mm", g.lower_lip_border_mm);
  number("lip_parting_mm", g.lip_parting_mm);
  if (g.nasal_spine_base) j["nasal_spine_base"] = vector_json(*g.nasal_spine_base);
  if (g.nasal_spine_tip) j["nasal_spine_tip"] = vector_json(*g.nasal_spine_tip);
  return j;
}

}  // namespace forensim
