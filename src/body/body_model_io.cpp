#include "body/body_model_io.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "geometry/tet_boundary.hpp"
#include "tet_io/vtu_reader.hpp"
#include "tet_io/vtu_writer.hpp"

namespace forensim {
namespace {

constexpr const char* format_name = "forensim body model";
constexpr int format_version = 1;

std::vector<double> as_doubles(const std::vector<int>& values) {
  return {values.begin(), values.end()};
}

/// An array `name` of `count` values that are integers in [lo, hi]; throws InputError naming the file.
std::vector<int> integer_field(const FieldSet& fields, const std::string& name, std::size_t count, double lo, double hi,
                               const std::string& source) {
  const auto it = fields.scalars.find(name);
  if (it == fields.scalars.end()) throw InputError(source, "array '" + name + "'", "is missing");
  if (it->second.size() != count)
    throw InputError(source, "array '" + name + "'",
                     "has " + std::to_string(it->second.size()) + " values, expected " + std::to_string(count));
  std::vector<int> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double v = it->second[i];
    if (!(v >= lo && v <= hi) || v != std::floor(v))
      throw InputError(
          source, "array '" + name + "' value " + std::to_string(i),
          "is " + std::to_string(v) + ", not an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    out[i] = static_cast<int>(v);
  }
  return out;
}

const std::vector<Vec3>& vector_field(const FieldSet& fields, const std::string& name, std::size_t count,
                                      const std::string& source) {
  const auto it = fields.vectors.find(name);
  if (it == fields.vectors.end()) throw InputError(source, "array '" + name + "'", "is missing");
  if (it->second.size() != count)
    throw InputError(source, "array '" + name + "'",
                     "has " + std::to_string(it->second.size()) + " values, expected " + std::to_string(count));
  return it->second;
}

}  // namespace

void write_body_model(const std::filesystem::path& folder, const BodyModel& model) {
  model.validate("body model");
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw IoError(folder.string(), "cannot create the folder: " + ec.message());

  TetMesh volume = model.volume;
  if (!model.tet_parts.empty()) volume.tet_fields.scalars["part"] = as_doubles(model.tet_parts);
  write_vtu(folder / "volume.vtu", volume);

  TriMesh skin = model.skin;
  const TrackingConnections& t = model.tracking;
  const std::size_t n = t.size();
  FieldSet& f = skin.vertex_fields;
  if (!model.skin_vertex_parts.empty()) f.scalars["part"] = as_doubles(model.skin_vertex_parts);
  std::vector<double>& face = f.scalars["tracking_face"];
  std::vector<double>& distance = f.scalars["tracking_rest_distance"];
  std::vector<double>& side = f.scalars["tracking_side"];
  std::vector<double>& method = f.scalars["tracking_method"];
  std::vector<Vec3>& nodes = f.vectors["tracking_nodes"];
  std::vector<Vec3>& weights = f.vectors["tracking_weights"];
  face.resize(n), distance.resize(n), side.resize(n), method.resize(n), nodes.resize(n), weights.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    face[i] = static_cast<double>(t.boundary_face[i]);
    distance[i] = t.rest_distance[i];
    side[i] = static_cast<double>(t.side[i]);
    method[i] = static_cast<double>(t.method[i]);
    nodes[i] = Vec3(t.face_nodes[i][0], t.face_nodes[i][1], t.face_nodes[i][2]);
    weights[i] = t.weights[i];
  }
  write_vtu(folder / "skin.vtu", skin);

  nlohmann::json json;
  json["format"] = format_name;
  json["version"] = format_version;
  json["units"] = "mm";
  json["volume"] = "volume.vtu";
  json["skin"] = "skin.vtu";
  json["parts"] = model.part_names;
  const auto triple = [](const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  json["pose"] = {{"views", model.pose.views},
                  {"up", triple(model.pose.up)},
                  {"front", triple(model.pose.front)},
                  {"gravity", triple(model.pose.gravity)}};
  json["counts"] = {{"volume_nodes", model.volume.vertex_count()},
                    {"tets", model.volume.tet_count()},
                    {"boundary_faces", model.boundary_faces.size()},
                    {"skin_vertices", model.skin.vertex_count()},
                    {"skin_triangles", model.skin.triangle_count()}};
  write_file_atomic(folder / "model.json", json.dump(2) + "\n");
}

BodyModel read_body_model(const std::filesystem::path& folder) {
  const std::filesystem::path json_path = folder / "model.json";
  const std::string source = json_path.string();
  if (!std::filesystem::exists(json_path))
    throw IoError(source, "not found: " + folder.string() + " is not a body model folder (no model.json)");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(read_file(json_path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source, "", std::string("is not valid JSON: ") + e.what());
  }
  const auto string_at = [&](const char* key) {
    if (!json.is_object() || !json.contains(key) || !json[key].is_string())
      throw InputError(source, std::string("key '") + key + "'", "is missing or not a string");
    return json[key].get<std::string>();
  };
  if (string_at("format") != format_name)
    throw InputError(source, "key 'format'", "is '" + string_at("format") + "', not '" + format_name + "'");
  if (!json.contains("version") || !json["version"].is_number_integer() || json["version"].get<int>() != format_version)
    throw InputError(source, "key 'version'", "must be " + std::to_string(format_version));
  if (string_at("units") != "mm") throw InputError(source, "key 'units'", "must be \"mm\"");
  const std::string volume_name = string_at("volume"), skin_name = string_at("skin");
  for (const std::string& name : {volume_name, skin_name}) {
    const std::filesystem::path p(name);
    if (p.empty() || p.is_absolute() || p.has_parent_path())
      throw InputError(source, "file '" + name + "'", "must be a plain file name inside the model folder");
  }
  BodyModel model;
  if (json.contains("parts")) {
    if (!json["parts"].is_array()) throw InputError(source, "key 'parts'", "must be an array of names");
    for (const auto& p : json["parts"]) {
      if (!p.is_string()) throw InputError(source, "key 'parts'", "must be an array of names");
      model.part_names.push_back(p.get<std::string>());
    }
  }
  if (json.contains("pose")) {
    const nlohmann::json& pose = json["pose"];
    if (!pose.is_object()) throw InputError(source, "key 'pose'", "must be an object");
    for (const auto& [key, value] : pose.items())
      if (key != "views" && key != "up" && key != "front" && key != "gravity")
        throw InputError(source, "key 'pose/" + key + "'", "is unknown (known: views, up, front, gravity)");
    if (pose.contains("views")) {
      if (!pose["views"].is_string()) throw InputError(source, "key 'pose/views'", "must be a string");
      model.pose.views = pose["views"].get<std::string>();
    }
    const auto vector_at = [&](const char* key, Vec3& v) {
      if (!pose.contains(key)) return;
      const nlohmann::json& a = pose[key];
      if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() || !a[2].is_number())
        throw InputError(source, std::string("key 'pose/") + key + "'", "must be three numbers [x, y, z]");
      v = Vec3(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
    };
    vector_at("up", model.pose.up);
    vector_at("front", model.pose.front);
    vector_at("gravity", model.pose.gravity);
  }
  const double part_max = static_cast<double>(model.part_names.size()) - 1.0;

  const std::string volume_source = (folder / volume_name).string();
  model.volume = read_vtu(folder / volume_name);
  if (model.volume.tet_fields.scalars.count("part")) {
    model.tet_parts =
        integer_field(model.volume.tet_fields, "part", model.volume.tet_count(), 0, part_max, volume_source);
    model.volume.tet_fields.scalars.erase("part");
  }

  const std::string skin_source = (folder / skin_name).string();
  model.skin = read_vtu_surface(folder / skin_name);
  FieldSet& f = model.skin.vertex_fields;
  const std::size_t n = model.skin.vertex_count();
  if (f.scalars.count("part")) {
    model.skin_vertex_parts = integer_field(f, "part", n, 0, part_max, skin_source);
    f.scalars.erase("part");
  }
  model.boundary_faces = tet_boundary_faces(model.volume);
  const double node_max = static_cast<double>(model.volume.vertex_count()) - 1.0;
  TrackingConnections& t = model.tracking;
  const std::vector<int> face =
      integer_field(f, "tracking_face", n, 0, static_cast<double>(model.boundary_faces.size()) - 1.0, skin_source);
  const std::vector<int> side = integer_field(f, "tracking_side", n, -1, 1, skin_source);
  const std::vector<int> method = integer_field(f, "tracking_method", n, 0, tracking_method_count - 1, skin_source);
  const std::vector<Vec3>& nodes = vector_field(f, "tracking_nodes", n, skin_source);
  const auto distance = f.scalars.find("tracking_rest_distance");
  if (distance == f.scalars.end() || distance->second.size() != n)
    throw InputError(skin_source, "array 'tracking_rest_distance'", "is missing or has the wrong length");
  t.boundary_face.assign(face.begin(), face.end());
  t.weights = vector_field(f, "tracking_weights", n, skin_source);
  t.rest_distance = distance->second;
  t.face_nodes.resize(n);
  t.side.resize(n);
  t.method.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const double v = nodes[i][k];
      if (!(v >= 0.0 && v <= node_max) || v != std::floor(v))
        throw InputError(skin_source, "array 'tracking_nodes' value " + std::to_string(i), "is not a node index");
      t.face_nodes[i][k] = static_cast<Index>(v);
    }
    if (side[i] == 0) throw InputError(skin_source, "array 'tracking_side' value " + std::to_string(i), "is 0");
    t.side[i] = side[i] < 0 ? TrackingSide::inside : TrackingSide::outside;
    t.method[i] = static_cast<TrackingMethod>(method[i]);
  }
  for (const char* name : {"tracking_face", "tracking_side", "tracking_method", "tracking_rest_distance"})
    f.scalars.erase(name);
  f.vectors.erase("tracking_nodes");
  f.vectors.erase("tracking_weights");
  model.validate(folder.string());
  return model;
}

}  // namespace forensim
