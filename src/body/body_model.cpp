#include "body/body_model.hpp"

#include <cmath>
#include <utility>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {
namespace {

void check_parts(const std::vector<int>& parts, std::size_t expected, std::size_t part_count, const std::string& source,
                 const char* what) {
  if (parts.empty()) return;
  if (parts.size() != expected)
    throw InputError(
        source, std::string(what) + " parts",
        "has " + std::to_string(parts.size()) + " entries for " + std::to_string(expected) + " " + what + "s");
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (parts[i] < 0 || static_cast<std::size_t>(parts[i]) >= part_count)
      throw InputError(
          source, std::string(what) + " " + std::to_string(i),
          "part " + std::to_string(parts[i]) + " is not one of the " + std::to_string(part_count) + " named parts");
}

}  // namespace

BodyPose BodyPose::of_phantom(const std::string& phantom) {
  BodyPose pose;
  if (phantom == "head") {
    pose.views = "head";
    pose.front = -Vec3::UnitY();
  }
  return pose;
}

void BodyPose::validate(const std::string& source) const {
  if (views != "arm" && views != "head") throw InputError(source, "pose views", "is '" + views + "', not arm or head");
  const auto unit = [&](const Vec3& v, const char* name) {
    if (!v.allFinite() || std::abs(v.norm() - 1.0) > 1e-6)
      throw InputError(source, std::string("pose ") + name, "must be a finite unit vector");
  };
  unit(up, "up");
  unit(front, "front");
  unit(gravity, "gravity");
  if (std::abs(up.dot(front)) > 1e-6) throw InputError(source, "pose up and front", "must be orthogonal");
}

void BodyModel::validate(const std::string& source) const {
  pose.validate(source);
  volume.validate(source + " (volume)");
  skin.validate(source + " (skin)");
  const std::vector<TetFace> expected = tet_boundary_faces(volume);
  if (expected.size() != boundary_faces.size())
    throw InputError(source, "boundary faces",
                     "has " + std::to_string(boundary_faces.size()) + " faces; the volume's boundary has " +
                         std::to_string(expected.size()));
  for (std::size_t f = 0; f < expected.size(); ++f)
    if (expected[f].vertices != boundary_faces[f].vertices || expected[f].tet != boundary_faces[f].tet)
      throw InputError(source, "boundary face " + std::to_string(f), "is not the volume's boundary face");
  validate_tracking(tracking, skin.vertex_count(), volume.vertex_count(), boundary_faces.size(), source);
  for (std::size_t i = 0; i < tracking.size(); ++i)
    if (tracking.face_nodes[i] != boundary_faces[tracking.boundary_face[i]].vertices)
      throw InputError(source, "tracking connection " + std::to_string(i),
                       "face nodes differ from those of boundary face " + std::to_string(tracking.boundary_face[i]));
  check_parts(skin_vertex_parts, skin.vertex_count(), part_names.size(), source, "skin vertex");
  check_parts(tet_parts, volume.tet_count(), part_names.size(), source, "tet");
}

void assign_parts(BodyModel& model, std::vector<std::string> part_names, const PartFunction& part_at) {
  if (!part_at) throw InputError("body model parts", "", "no part function given");
  std::vector<int> skin_parts(model.skin.vertex_count());
  parallel_for(0, skin_parts.size(), [&](std::size_t i) { skin_parts[i] = part_at(model.skin.positions[i]); });
  std::vector<int> tet_parts(model.volume.tet_count());
  parallel_for(0, tet_parts.size(), [&](std::size_t t) {
    const Tet& k = model.volume.tets[t];
    const std::vector<Vec3>& x = model.volume.positions;
    tet_parts[t] = part_at(0.25 * (x[k[0]] + x[k[1]] + x[k[2]] + x[k[3]]));
  });
  check_parts(skin_parts, skin_parts.size(), part_names.size(), "body model parts", "skin vertex");
  check_parts(tet_parts, tet_parts.size(), part_names.size(), "body model parts", "tet");
  model.part_names = std::move(part_names);
  model.skin_vertex_parts = std::move(skin_parts);
  model.tet_parts = std::move(tet_parts);
}

BodyModel make_body_model(TetMesh volume, TriMesh skin, std::vector<std::string> part_names,
                          const PartFunction& part_at, const TrackingOptions& options) {
  BodyModel model;
  volume.validate("body model volume");
  model.boundary_faces = tet_boundary_faces(volume);
  model.tracking = compute_tracking(skin, volume, model.boundary_faces, options);  // validates the skin
  model.volume = std::move(volume);
  model.skin = std::move(skin);
  if (part_at)
    assign_parts(model, std::move(part_names), part_at);
  else
    model.part_names = std::move(part_names);
  return model;
}

}  // namespace forensim
