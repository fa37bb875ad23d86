#include "craniofacial/skull_input.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <numeric>

#include "core/error.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "mesh_processing/decimate.hpp"
#include "volume/half_maximum_height.hpp"
#include "volume/iso_surface.hpp"
#include "volume/volume_reader.hpp"

namespace forensim {
namespace {

constexpr double k_default_bone_iso_hu = 126.0;  // 1150 in HU + 1024 storage (VTK medical examples)
constexpr double k_hu_storage_offset = 1024.0;
/// Fewer plateau profiles than this and the half-maximum height is not trusted (noise specks, a bone fragment).
constexpr std::size_t k_min_threshold_profiles = 200;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// The largest components, at most `max_components`, each at least `fraction` of the largest one's area.
TriMesh select_components(const TriMesh& mesh, const SkullInputOptions& options, Skull& skull) {
  int count = 0;
  const std::vector<int> component = triangle_components(mesh, &count);
  skull.components_found = count;
  std::vector<double> area(static_cast<std::size_t>(count), 0.0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& f = mesh.triangles[t];
    area[static_cast<std::size_t>(component[t])] +=
        triangle_area(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]);
  }
  std::vector<int> order(static_cast<std::size_t>(count));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] > area[b]; });
  std::vector<bool> keep_component(static_cast<std::size_t>(count), false);
  int kept = 0;
  for (int c : order) {
    if (kept >= std::max(1, options.max_components)) break;
    if (kept > 0 && area[c] < options.min_component_area_fraction * area[order.front()]) break;
    keep_component[static_cast<std::size_t>(c)] = true;
    ++kept;
  }
  skull.components_kept = kept;
  if (kept == count) return mesh;
  skull.notes.push_back(fmt::format("kept the {} largest of {} connected components", kept, count));
  std::vector<bool> keep(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) keep[t] = keep_component[component[t]];
  return extract_triangles(mesh, keep);
}

}  // namespace

bool is_volume_path(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return true;
  const std::string name = lower(path.filename().string());
  for (const char* ext : {".nrrd", ".nhdr", ".mhd", ".mha", ".dcm", ".tif", ".tiff"}) {
    const std::string e(ext);
    if (name.size() >= e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) return true;
  }
  std::ifstream in(path, std::ios::binary);
  char header[132] = {};
  if (in.read(header, sizeof(header)) && std::string(header + 128, 4) == "DICM") return true;
  return false;
}

Skull skull_from_mesh(TriMesh mesh, const std::string& source, const SkullInputOptions& options) {
  mesh.validate(source);
  if (mesh.triangles.empty()) throw InputError(source, "", "skull mesh has no triangles");
  Skull skull;
  skull.source = source;
  skull.kind = "mesh";
  skull.input_triangles = mesh.triangles.size();
  mesh = select_components(mesh, options, skull);
  const TopologyReport topology = check_topology(mesh);
  if (topology.is_closed() && enclosed_volume(mesh) < 0.0) {
    for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
    for (Tri& t : mesh.triangle_uvs) std::swap(t[1], t[2]);
    skull.notes.push_back("triangles faced inward (negative enclosed volume); turned outward");
  } else if (!topology.is_closed()) {
    skull.notes.push_back("skull mesh is open (" + topology.summary() + "); normals follow its triangle order");
  }
  if (options.max_triangles > 0 && mesh.triangles.size() > options.max_triangles) {
    const std::size_t before = mesh.triangles.size();
    mesh = decimate(mesh, options.max_triangles);
    skull.notes.push_back(fmt::format("decimated from {} to {} triangles", before, mesh.triangles.size()));
  }
  if (mesh.triangles.size() < options.min_triangles) {
    skull.notes.push_back(fmt::format("{} triangles: coarser than the paper's 50k-250k", mesh.triangles.size()));
  }
  compute_normals(mesh);
  const double diagonal = bounding_box(mesh.positions).diagonal();
  if (diagonal < 100.0 || diagonal > 600.0) {
    skull.notes.push_back(
        fmt::format("bounding-box diagonal {:.0f} mm is far from an adult skull's (about 250-350 "
                    "mm): check the mesh units",
                    diagonal));
  }
  skull.mesh = std::move(mesh);
  return skull;
}

BoneSurface extract_bone_surface(const ScalarGrid& volume, const std::string& source,
                                 const SkullInputOptions& options) {
  volume.validate(source);
  BoneSurface bone;
  const bool measure = !options.bone_iso_value && options.half_maximum_height;
  if (options.bone_iso_value) {
    bone.iso_value = *options.bone_iso_value;
    if (!std::isfinite(bone.iso_value)) throw InputError(source, "bone iso-value", "is not finite");
  } else {
    const auto [lo, hi] = volume.value_range();
    (void)hi;
    const bool offset_storage = lo >= -100.0f;
    bone.iso_value = k_default_bone_iso_hu + (offset_storage ? k_hu_storage_offset : 0.0);
    bone.notes.push_back(fmt::format("bone {} iso-value {} ({} HU{})", measure ? "found at" : "surface at",
                                     bone.iso_value, k_default_bone_iso_hu,
                                     offset_storage ? ", volume stored as HU + 1024" : ""));
  }
  IsoSurfaceOptions iso_options;
  iso_options.smoothing_iterations = options.smoothing_iterations;
  bone.surface = extract_iso_surface(volume, bone.iso_value, iso_options);
  if (bone.surface.triangles.empty()) {
    throw InputError(source, fmt::format("iso-value {}", bone.iso_value), "no voxel lies above the bone iso-value");
  }
  if (!measure) return bone;
  HalfMaximumOptions hmh_options;
  hmh_options.iso_value = bone.iso_value;
  const std::vector<EdgeProfile> profiles = measure_edge_profiles(bone.surface, volume, hmh_options);
  const HalfMaximumHeight hmh = half_maximum_height(profiles);
  if (hmh.used < k_min_threshold_profiles) {
    bone.notes.push_back(
        fmt::format("half-maximum height not used ({} plateau profiles of {}, level {:.0f}): "
                    "surface at {}",
                    hmh.used, hmh.profiles, hmh.level, bone.iso_value));
    return bone;
  }
  const HalfMaximumMoves moves = move_to_half_maximum(bone.surface, profiles, hmh.level, hmh.peak);
  bone.notes.push_back(fmt::format(
      "bone surface moved to its half-maximum height {:.0f} (SD {:.0f}; mean over {} plateau profiles across the {} "
      "surface, bone {:.0f}, beside it {:.0f}): {} vertices to it, {} of thinner bone to the plate model's edge, "
      "mean move {:+.2f} mm, {} cut to a voxel",
      hmh.level, hmh.level_sd, hmh.used, bone.iso_value, hmh.peak, hmh.background, moves.to_level, moves.to_own,
      moves.mean_shift_mm, moves.capped));
  bone.seed_iso_value = bone.iso_value;
  bone.threshold_profiles = hmh.used;
  bone.iso_value = hmh.level;
  return bone;
}

Skull skull_from_volume(const ScalarGrid& volume, const std::string& source, const SkullInputOptions& options) {
  BoneSurface bone = extract_bone_surface(volume, source, options);
  Skull skull = skull_from_mesh(std::move(bone.surface), source, options);
  skull.kind = "ct";
  skull.iso_value = bone.iso_value;
  skull.seed_iso_value = bone.seed_iso_value;
  skull.threshold_profiles = bone.threshold_profiles;
  skull.field_of_view = ScanFieldOfView::of_volume(volume);
  for (std::string& n : skull.notes) bone.notes.push_back(std::move(n));
  skull.notes = std::move(bone.notes);
  return skull;
}

Skull load_skull(const std::filesystem::path& path, const SkullInputOptions& options) {
  if (is_volume_path(path)) {
    if (!std::filesystem::exists(path)) throw IoError(path.string(), "does not exist");
    return skull_from_volume(read_volume(path), path.string(), options);
  }
  ImportedMesh imported = import_mesh_with_textures(path, options.mesh_units);
  Skull skull = skull_from_mesh(std::move(imported.mesh), path.string(), options);
  skull.mm_per_unit = imported.mm_per_unit;
  return skull;
}

}  // namespace forensim
