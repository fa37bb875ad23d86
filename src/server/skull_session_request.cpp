#include "server/skull_session_request.hpp"

#include <cmath>
#include <vector>

#include "core/error.hpp"
#include "craniofacial/face_guides_job.hpp"
#include "server/api_error.hpp"
#include "server/served_path.hpp"

namespace forensim {
namespace {

// A served file named by a request field, or the ApiError that answers it.
std::string served_file(const std::filesystem::path& root, const std::string& relative, const std::string& field,
                        const std::string& what) {
  const ServedPath p = resolve_served_path(root, relative);
  switch (p.problem) {
    case ServedPathProblem::none:
      return p.path.string();
    case ServedPathProblem::malformed:
      throw ApiError(400, p.message + " (" + what + ")", field);
    case ServedPathProblem::outside:
      throw ApiError(403, p.message, field);
    case ServedPathProblem::missing:
      throw ApiError(404, p.message + " (" + what + ")", field);
  }
  throw ApiError(500, "unreachable");
}

SkullDepthChoice depth_choice(const JobNode& root, const std::filesystem::path& served_root) {
  SkullDepthChoice d;
  d.table_label = root.get<std::string>("table", d.table);
  d.table = d.table_label == "ttable_2023" || d.table_label == "rhine_1983"
                ? d.table_label
                : served_file(served_root, d.table_label, root.path() + "/table",
                              "a table is ttable_2023, rhine_1983 or a CSV file in the served folder");
  d.sex = root.get_choice("sex", "", {"", "female", "male", "pooled"});
  d.build = root.get_choice("build", "", {"", "slender", "normal", "obese"});
  return d;
}

}  // namespace

JobDocument parse_request(const std::string& text, const std::string& what) {
  nlohmann::json probe = nlohmann::json::parse(text, nullptr, false);
  if (probe.is_discarded()) {
    // The loader's message gives the line and column.
    try {
      return JobDocument::parse(text, what);
    } catch (const JobError& e) {
      throw ApiError(400, e.what());
    } catch (const nlohmann::json::exception& e) {  // a number out of double's range
      throw ApiError(400, what + ": " + e.what());
    }
  }
  if (!probe.is_object()) throw ApiError(400, what + ": expected a JSON object, got " + probe.type_name());
  return JobDocument::parse(text, what);
}

SkullSessionRequest read_skull_session_request(const JobNode& root, const std::filesystem::path& served_root) {
  SkullSessionRequest r;
  r.skull_label = root.get<std::string>("skull", r.skull);
  r.skull = r.skull_label == "builtin" ? r.skull_label
                                       : served_file(served_root, r.skull_label, "/skull",
                                                     "a skull is builtin or a mesh or CT file in the served folder");
  r.unit = root.get_choice("unit", r.unit, {"auto", "m", "cm", "mm", "in"});
  r.landmarks_label = root.get<std::string>("landmarks", r.landmarks);
  if (r.landmarks_label == "auto" || r.landmarks_label == "template") {
    r.landmarks = r.landmarks_label;
  } else {
    r.landmarks = served_file(served_root, r.landmarks_label, "/landmarks",
                              "landmarks are auto, template or a .mrk.json or .csv file in the served folder");
  }
  if (r.landmarks == "template" && r.skull != "builtin") {
    root.fail("landmarks", "only the built-in skull carries the template's landmarks; give 'auto' or a file");
  }
  r.depths = depth_choice(root, served_root);
  r.template_detail = root.get_choice("template_detail", r.template_detail, {"full", "coarse"});
  r.interpolated_landmarks = root.get<bool>("interpolated_landmarks", r.interpolated_landmarks);
  if (root.has("guides")) {
    const FaceGuides g = read_face_guides(root.child("guides"));
    if (any_guide(g)) r.guides = g;
  }
  return r;
}

LandmarkEdit read_landmark_edit(const JobNode& root) {
  LandmarkEdit e;
  e.name = root.require<std::string>("name");
  if (e.name.empty()) root.fail("name", "must not be empty");
  const auto values = root.require<std::vector<double>>("position");
  if (values.size() != 3)
    root.fail("position", "expected [x, y, z] in mm, got " + std::to_string(values.size()) + " numbers");
  for (double v : values) {
    if (!std::isfinite(v) || std::abs(v) > kMaxCoordinateMm) {
      root.fail("position", "coordinates must be finite numbers within 1e5 mm");
    }
  }
  e.position_mm = Vec3(values[0], values[1], values[2]);
  return e;
}

SkullDepthChoice read_depth_choice(const JobNode& root, const std::filesystem::path& served_root) {
  return depth_choice(root, served_root);
}

std::optional<FaceGuides> read_guides_request(const JobNode& root) {
  if (!root.has("guides")) return std::nullopt;
  {
    // null switches the guides off.
    const nlohmann::json value = root.get<nlohmann::json>("guides", nullptr);
    if (value.is_null()) return std::nullopt;
    if (!value.is_object()) root.fail("guides", std::string("expected an object or null, got ") + value.type_name());
  }
  const FaceGuides g = read_face_guides(root.child("guides"));
  if (!any_guide(g)) return std::nullopt;
  return g;
}

}  // namespace forensim
