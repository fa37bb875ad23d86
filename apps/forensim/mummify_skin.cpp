#include "mummify_skin.hpp"

#include <cmath>
#include <cstdio>

#include "body/tracking.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "image/png_io.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "pictures.hpp"
#include "render/sheet.hpp"
#include "skin/skin_moisture.hpp"
#include "tet_io/vtu_reader.hpp"
#include "tet_io/vtu_writer.hpp"

namespace forensim::cli {
namespace {

/// "skin/frame_" and 3 -> "skin/frame_0003" + extension.
std::string numbered(const std::string& prefix, int index, const std::string& extension) {
  char digits[16];
  std::snprintf(digits, sizeof digits, "%04d", index);
  return prefix + digits + extension;
}

LivorState start_state(const TriMesh& skin, const SkinShadingJob& job) {
  LivorSettings settings = job.livor;
  settings.gravity = job.gravity;
  const std::vector<std::uint8_t> contact = job.contact_distance_mm >= 0.0
                                                ? contact_near_plane(skin, job.gravity, job.contact_distance_mm)
                                                : std::vector<std::uint8_t>{};
  return settle_livor(skin, contact, settings);
}

/// #S vertex areas (one third of each adjacent triangle), mm^2.
std::vector<double> vertex_areas(const TriMesh& mesh) {
  std::vector<double> area(mesh.positions.size(), 0.0);
  for (const Tri& t : mesh.triangles) {
    const Vec3& a = mesh.positions[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.positions[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.positions[static_cast<std::size_t>(t[2])];
    const double third = (b - a).cross(c - a).norm() / 6.0;
    for (Index v : t) area[static_cast<std::size_t>(v)] += third;
  }
  return area;
}

}  // namespace

std::vector<Vec3> skin_rest_offsets(const BodyModel& body) {
  const std::vector<Vec3> points = tracking_points(body.tracking, body.volume.positions);
  std::vector<Vec3> offsets(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) offsets[i] = body.skin.positions[i] - points[i];
  return offsets;
}

std::vector<Vec3> skin_positions_for_frame(const BodyModel& body, const std::vector<Vec3>& rest_offsets,
                                           const std::vector<Vec3>& node_positions) {
  std::vector<Vec3> positions = tracking_points(body.tracking, node_positions);
  require_input(
      rest_offsets.size() == positions.size(), "skin", "rest offsets",
      std::to_string(rest_offsets.size()) + " offsets for " + std::to_string(positions.size()) + " skin vertices");
  for (std::size_t i = 0; i < positions.size(); ++i) positions[i] += rest_offsets[i];
  return positions;
}

MummifySkin::MummifySkin(const BodyModel& body, double initial_moisture, const SkinShadingJob& job)
    : m_body(body),
      m_initial_moisture(initial_moisture),
      m_shader(job.shading),
      m_livor(start_state(body.skin, job)),
      m_layers(uniform_skin_layers(body.skin.vertex_count())) {
  if (body.skin.has_uvs() && job.map_resolution > 0) m_baker.emplace(body.skin, job.map_resolution);
}

SkinFrame MummifySkin::frame(const DesiccationState& state, const std::vector<Vec3>& positions) const {
  require_input(
      positions.size() == m_body.skin.vertex_count(), "skin frame", "positions",
      std::to_string(positions.size()) + " for " + std::to_string(m_body.skin.vertex_count()) + " skin vertices");
  SkinFrame f;
  f.day = state.time_s / 86400.0;
  f.positions = positions;
  skin_moisture_ratio(m_body.tracking.face_nodes, m_body.tracking.weights, state.node_moisture, m_initial_moisture,
                      f.moisture);
  m_shader.shade(m_layers, m_livor, f.moisture, state.time_s / 3600.0, f.colours);
  return f;
}

std::string MummifySkin::write_frame(const std::filesystem::path& run_folder, const SkinFrame& frame, int index) const {
  TriMesh mesh;
  mesh.positions = frame.positions;
  mesh.triangles = m_body.skin.triangles;
  const std::size_t n = mesh.positions.size();
  std::vector<Vec3> colour(n);
  for (std::size_t i = 0; i < n; ++i) colour[i] = frame.colours[i].head<3>().cast<double>();
  mesh.vertex_fields.vectors["colour"] = colour;
  mesh.vertex_fields.scalars["moisture_ratio"] = frame.moisture;
  mesh.vertex_fields.scalars["livor_hemoglobin"] = m_livor.vertex_hemoglobin;
  mesh.vertex_fields.scalars["livor_saturation"] = m_livor.vertex_saturation;
  mesh.vertex_fields.scalars["livor_capacity"] = m_livor.vertex_capacity;
  mesh.vertex_fields.scalars["livor_contact"] =
      std::vector<double>(m_livor.vertex_contact.begin(), m_livor.vertex_contact.end());
  if (!m_body.skin_vertex_parts.empty())
    mesh.vertex_fields.scalars["part"] =
        std::vector<double>(m_body.skin_vertex_parts.begin(), m_body.skin_vertex_parts.end());
  const std::string name = numbered("skin/frame_", index, ".vtu");
  std::filesystem::create_directories(run_folder / "skin");
  VtuOptions options;
  options.compress = true;  // float64 points and fields: a frame read back (on --resume) is the frame written
  write_vtu(run_folder / name, mesh, options);
  if (m_baker) write_png(run_folder / numbered("skin/colour_", index, ".png"), m_baker->bake_colours(frame.colours));
  return name;
}

SkinFrame read_skin_frame(const std::filesystem::path& vtu, std::size_t vertex_count, double day) {
  TriMesh mesh = read_vtu_surface(vtu);
  const auto colour = mesh.vertex_fields.vectors.find("colour");
  const auto moisture = mesh.vertex_fields.scalars.find("moisture_ratio");
  require_input(mesh.positions.size() == vertex_count && colour != mesh.vertex_fields.vectors.end() &&
                    moisture != mesh.vertex_fields.scalars.end(),
                vtu.string(), "", "not a skin frame of this model (vertex count or colour/moisture fields differ)");
  SkinFrame f;
  f.day = day;
  f.positions = std::move(mesh.positions);
  f.moisture = moisture->second;
  f.colours.resize(vertex_count);
  for (std::size_t i = 0; i < vertex_count; ++i)
    f.colours[i] = Vec4f(static_cast<float>(colour->second[i][0]), static_cast<float>(colour->second[i][1]),
                         static_cast<float>(colour->second[i][2]), 1.0f);
  return f;
}

TriMesh skin_mesh_of_frame(const TriMesh& rest_skin, const SkinFrame& frame) {
  TriMesh mesh = rest_skin;
  mesh.positions = frame.positions;
  mesh.colors = frame.colours;
  mesh.vertex_fields = {};
  mesh.triangle_fields = {};
  mesh.material = Material{};
  mesh.material.name = "skin";
  mesh.material.roughness = 0.55f;
  compute_normals(mesh);
  return mesh;
}

void write_skin_glb(const std::filesystem::path& path, const TriMesh& rest_skin, const std::vector<SkinFrame>& frames,
                    const std::vector<std::string>& map_pngs) {
  require_input(!frames.empty(), path.string(), "", "no skin frames");
  require_input(map_pngs.empty() || map_pngs.size() == frames.size(), path.string(), "maps",
                "one colour map per frame expected");
  const std::size_t count = frames.size();
  std::vector<TriMesh> meshes;
  meshes.reserve(count);
  for (const SkinFrame& f : frames) meshes.push_back(skin_mesh_of_frame(rest_skin, f));
  GltfScene scene;
  std::vector<double> times(count);
  for (std::size_t k = 0; k < count; ++k) times[k] = static_cast<double>(k);
  for (std::size_t k = 0; k < count; ++k) {
    GltfMeshNode node;
    char name[64];
    std::snprintf(name, sizeof name, "skin frame %zu (day %.2f)", k, frames[k].day);
    node.name = name;
    node.mesh = meshes[k];
    node.mesh.material.name = name;
    if (!map_pngs.empty()) {
      node.mesh.colors.clear();  // COLOR_0 would multiply the map
      node.textures.base_color_png = map_pngs[k];
    }
    node.scale = k == 0 ? 1.0 : 0.0;
    if (k + 1 < count) {
      MorphTarget target;
      target.name = "to frame " + std::to_string(k + 1);
      target.position_deltas.resize(meshes[k].positions.size());
      target.normal_deltas.resize(meshes[k].positions.size());
      for (std::size_t v = 0; v < target.position_deltas.size(); ++v) {
        target.position_deltas[v] = meshes[k + 1].positions[v] - meshes[k].positions[v];
        target.normal_deltas[v] = meshes[k + 1].normals[v] - meshes[k].normals[v];
      }
      node.morph_targets.push_back(std::move(target));
      scene.animations.push_back({"drying", k, {times[k], times[k + 1]}, {{0.0}, {1.0}}, GltfInterpolation::linear});
    }
    std::vector<double> scales(count, 0.0);
    scales[k] = 1.0;
    scene.scale_animations.push_back({"drying", k, times, scales, GltfInterpolation::step});
    scene.nodes.push_back(std::move(node));
  }
  write_gltf(path, scene);
}

double mean_skin_moisture(const TriMesh& rest_skin, const SkinFrame& frame) {
  const std::vector<double> area = vertex_areas(rest_skin);
  double sum = 0.0, total = 0.0;
  for (std::size_t i = 0; i < area.size() && i < frame.moisture.size(); ++i) {
    sum += area[i] * frame.moisture[i];
    total += area[i];
  }
  return total > 0.0 ? sum / total : 0.0;
}

Image skin_timeline_sheet(const TriMesh& rest_skin, const std::vector<SkinFrame>& frames, const ViewAxes& axes,
                          ViewName view, const RenderSettings& settings, const std::string& title) {
  require_input(!frames.empty(), "skin timeline", "", "no skin frames");
  // Fresh (the start), fully dried (the end) and partly dried: the frame whose mean skin moisture is nearest
  // the middle of the two.
  const std::size_t last = frames.size() - 1;
  const double middle =
      0.5 * (mean_skin_moisture(rest_skin, frames.front()) + mean_skin_moisture(rest_skin, frames.back()));
  std::size_t partly = last / 2;
  for (std::size_t k = 0; k <= last; ++k)
    if (std::abs(mean_skin_moisture(rest_skin, frames[k]) - middle) <
        std::abs(mean_skin_moisture(rest_skin, frames[partly]) - middle))
      partly = k;
  const std::size_t picks[3] = {0, partly, last};
  std::vector<SheetCell> cells;
  for (std::size_t pick : picks) {
    const SkinFrame& f = frames[pick];
    Scene scene;
    const TriMesh mesh = skin_mesh_of_frame(rest_skin, f);
    scene.add(mesh, material_from_name("vertex", mesh));
    char caption[64];
    std::snprintf(caption, sizeof caption, "day %.1f, m %.2f", f.day, mean_skin_moisture(rest_skin, f));
    cells.push_back({render_view(std::move(scene), settings, to_string(view), axes), caption});
  }
  return make_sheet(cells, 3, title);
}

Image skin_turntable_sheet(const TriMesh& rest_skin, const SkinFrame& frame, const ViewAxes& axes, int count,
                           const RenderSettings& settings, const std::string& title) {
  Scene scene;
  const TriMesh mesh = skin_mesh_of_frame(rest_skin, frame);
  scene.add(mesh, material_from_name("vertex", mesh));
  FramingOptions framing;
  framing.axes = axes;
  const std::vector<Image> images = render_turntable(scene, settings, count, 15.0, framing);
  std::vector<SheetCell> cells;
  for (std::size_t k = 0; k < images.size(); ++k)
    cells.push_back({images[k], std::to_string(360 * static_cast<int>(k) / count) + " deg"});
  return make_sheet(cells, std::min(count, 4), title);
}

Vec3 mean_skin_colour(const TriMesh& rest_skin, const SkinFrame& frame) {
  const std::vector<double> area = vertex_areas(rest_skin);
  Vec3 sum = Vec3::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < area.size() && i < frame.colours.size(); ++i) {
    sum += area[i] * frame.colours[i].head<3>().cast<double>();
    total += area[i];
  }
  return total > 0.0 ? Vec3(sum / total) : Vec3::Zero();
}

}  // namespace forensim::cli
