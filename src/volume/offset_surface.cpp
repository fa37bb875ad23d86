#include "volume/offset_surface.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "volume/taubin_smooth.hpp"
#include "volume/vdb_polygons.hpp"

namespace forensim {

TriMesh inner_offset_surface(const TriMesh& skin, const InnerOffsetOptions& options, const std::string& source) {
  require_input(std::isfinite(options.depth_mm) && options.depth_mm > 0.0 && options.depth_mm <= 1000.0, source,
                "offset depth", "must be in (0, 1000] mm");
  require_input(std::isfinite(options.voxel_mm) && options.voxel_mm >= 0.0 && options.voxel_mm <= 100.0, source,
                "offset voxel size", "must be in [0, 100] mm (0: automatic)");
  require_input(options.keep_largest_components >= 0 && options.smoothing_iterations >= 0, source, "offset options",
                "component and smoothing counts must not be negative");
  skin.validate(source);
  require_input(skin.triangle_count() > 0, source, "mesh", "has no triangles");
  const TopologyReport topology = check_topology(skin);
  require_input(topology.is_closed(), source, "mesh",
                "must be closed to have an inside (" + topology.summary() + "); repair it or close its openings");
  for (const Vec3& p : skin.positions) require_input(p.allFinite(), source, "vertex positions", "must be finite");

  const double voxel = options.voxel_mm > 0.0 ? options.voxel_mm : std::clamp(options.depth_mm / 2.0, 0.5, 3.0);
  // The narrow band holds about area / voxel^2 voxels per voxel of band width: refuse sizes that would take
  // gigabytes (a skin in the wrong unit, or a depth far larger than the body needs).
  const float inside_band = static_cast<float>(options.depth_mm / voxel + 3.0);
  const double band_voxels = surface_area(skin) / (voxel * voxel) * (inside_band + 3.0);
  constexpr double max_band_voxels = 1.5e8;  // about 3 GB of OpenVDB leaves and mesher state
  if (band_voxels > max_band_voxels) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "would need about %.0f million level-set voxels (skin area %.3g mm^2, voxel %.2f mm, band %.0f "
                  "voxels); is the skin's unit right?",
                  band_voxels / 1e6, surface_area(skin), voxel, inside_band + 3.0);
    throw InputError(source, "offset surface", text);
  }
  openvdb::initialize();
  const openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(voxel);
  std::vector<openvdb::Vec3s> points;
  points.reserve(skin.positions.size());
  for (const Vec3& p : skin.positions)
    points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(skin.triangles.size());
  for (const Tri& t : skin.triangles)
    triangles.emplace_back(static_cast<openvdb::Index32>(t[0]), static_cast<openvdb::Index32>(t[1]),
                           static_cast<openvdb::Index32>(t[2]));
  const std::vector<openvdb::Vec4I> no_quads;
  // Band widths in voxels: a little outside, and past the offset depth inside (inside_band above) so the
  // iso-value -depth lies within the band with room for the mesher's interpolation.
  const openvdb::FloatGrid::Ptr sdf = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
      *xform, points, triangles, no_quads, 3.0f, inside_band);
  std::vector<openvdb::Vec3s> out_points;
  std::vector<openvdb::Vec3I> out_triangles;
  std::vector<openvdb::Vec4I> out_quads;
  openvdb::tools::volumeToMesh(*sdf, out_points, out_triangles, out_quads, -options.depth_mm, 0.0, false);

  std::vector<Vec3> positions;
  positions.reserve(out_points.size());
  for (const auto& p : out_points) positions.emplace_back(p.x(), p.y(), p.z());
  // The polygons of a signed-distance level set wind clockwise seen from outside (its positive side): reversed.
  TriMesh mesh = mesh_from_vdb_polygons(std::move(positions), out_triangles, out_quads, true);
  require_input(mesh.triangle_count() > 0, source, "offset surface",
                "is empty: no part of the body is thicker than twice the offset depth of " +
                    std::to_string(options.depth_mm) + " mm");
  if (options.keep_largest_components > 0) mesh = keep_largest_components(mesh, options.keep_largest_components);
  if (options.smoothing_iterations > 0) taubin_smooth(mesh, options.smoothing_iterations);
  compute_normals(mesh);
  return mesh;
}

}  // namespace forensim
