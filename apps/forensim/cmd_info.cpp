// forensim info: what a mesh, tet mesh or volume file holds (counts, size in mm, topology, value range).

#include <nlohmann/json.hpp>

#include <cstdio>

#include "cli_common.hpp"
#include "commands.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "geometry/tet_boundary.hpp"
#include "mesh_io/mesh_import.hpp"

#include "volume/volume_reader.hpp"

namespace forensim::cli {
namespace {

nlohmann::json surface_info(const TriMesh& mesh) {
  const TopologyReport topology = check_topology(mesh);
  const BoundingBox box = bounding_box(mesh.positions);
  nlohmann::json j;
  j["kind"] = "surface mesh";
  j["vertices"] = mesh.vertex_count();
  j["triangles"] = mesh.triangle_count();
  j["size_mm"] = {box.size().x(), box.size().y(), box.size().z()};
  j["area_mm2"] = surface_area(mesh);
  if (topology.is_closed()) j["enclosed_volume_mm3"] = enclosed_volume(mesh);
  j["topology"] = topology.summary();
  j["closed"] = topology.is_closed();
  j["manifold"] = topology.is_manifold();
  j["components"] = topology.component_count;
  j["has_uvs"] = mesh.has_uvs();
  j["has_normals"] = mesh.has_normals();
  j["has_colors"] = mesh.has_colors();
  if (!mesh.material.base_color_texture.empty()) j["base_color_texture"] = mesh.material.base_color_texture;
  return j;
}

nlohmann::json tet_info(const TetMesh& mesh) {
  nlohmann::json j;
  j["kind"] = "tetrahedral mesh";
  j["nodes"] = mesh.vertex_count();
  j["tets"] = mesh.tet_count();
  const BoundingBox box = bounding_box(mesh.positions);
  j["size_mm"] = {box.size().x(), box.size().y(), box.size().z()};
  j["volume_mm3"] = tet_mesh_volume(mesh);
  std::map<int, std::size_t> labels;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) ++labels[mesh.label(t)];
  for (const auto& [label, count] : labels) {
    j["labels"][std::to_string(label)] = {{"tets", count}, {"volume_mm3", tet_mesh_volume(mesh, label)}};
  }
  std::size_t inverted = 0;
  for (const Tet& t : mesh.tets) {
    if (tet_signed_volume(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]) <=
        0) {
      ++inverted;
    }
  }
  j["inverted_or_flat_tets"] = inverted;
  j["boundary"] = check_topology(tet_boundary_mesh(mesh)).summary();
  for (const auto& [name, values] : mesh.vertex_fields.scalars) j["node_fields"].push_back(name);
  for (const auto& [name, values] : mesh.tet_fields.scalars) j["tet_fields"].push_back(name);
  return j;
}

nlohmann::json volume_info(const ScalarGrid& grid) {
  nlohmann::json j;
  j["kind"] = "volume";
  j["samples"] = {grid.nx, grid.ny, grid.nz};
  j["spacing_mm"] = {grid.spacing.x(), grid.spacing.y(), grid.spacing.z()};
  j["origin_mm"] = {grid.origin.x(), grid.origin.y(), grid.origin.z()};
  const Vec3 size = grid.world_bounds().size();
  j["size_mm"] = {size.x(), size.y(), size.z()};
  const auto [lo, hi] = grid.value_range();
  j["value_range"] = {lo, hi};
  return j;
}

// Text form of a value: numbers with at most 2 decimals.
std::string value_text(const nlohmann::json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f", v.get<double>());
    return buf;
  }
  if (v.is_array()) {
    std::string out;
    for (const auto& e : v) out += (out.empty() ? "" : " x ") + value_text(e);
    return out;
  }
  if (v.is_object()) {
    std::string out;
    for (auto it = v.begin(); it != v.end(); ++it)
      out += (out.empty() ? "" : ", ") + it.key() + ": " + value_text(it.value());
    return "{" + out + "}";
  }
  return v.dump();
}

void print_text(const nlohmann::json& j, const std::string& path) {
  std::printf("%s: %s\n", path.c_str(), j["kind"].get<std::string>().c_str());
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it.key() == "kind") continue;
    std::printf("  %-22s %s\n", it.key().c_str(),
                it.value().is_string() ? it.value().get<std::string>().c_str() : it.value().dump().c_str());
  }
}

const RegisterCommand info_command{
    "info", [](CLI::App& app) {
      auto* sub =
          app.add_subcommand("info", "Describe a mesh, tetrahedral mesh or volume: counts, size in mm, topology");
      auto path = std::make_shared<std::string>();
      auto unit = std::make_shared<std::string>("auto");
      auto json = std::make_shared<bool>(false);
      sub->add_option("path", *path,
                      "Mesh (OBJ, PLY, STL, glTF, FBX...), tet mesh (.msh, .node/.ele, .vtu) or volume "
                      "(.nrrd, .nhdr, .mhd, DICOM folder)")
          ->required();
      sub->add_option("--unit", *unit, "Unit of a surface mesh file: auto, m, cm, mm or in");
      sub->add_flag("--json", *json, "Print JSON instead of text");
      return [=]() {
        nlohmann::json j;
        switch (classify_path(*path)) {
          case DataKind::surface_mesh:
            j = surface_info(import_mesh(*path, {*unit, 0.0}));
            break;
          case DataKind::tet_mesh:
            j = tet_info(read_tet_mesh(*path));
            break;
          case DataKind::volume:
            j = volume_info(read_volume(*path));
            break;
        }
        if (*json) {
          std::printf("%s\n", j.dump(2).c_str());
        } else {
          print_text(j, *path);
        }
        return 0;
      };
    }};

}  // namespace
}  // namespace forensim::cli
