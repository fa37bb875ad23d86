#include "volume/iso_surface.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <cmath>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "volume/taubin_smooth.hpp"
#include "volume/vdb_polygons.hpp"

namespace forensim {

TriMesh extract_iso_surface(const ScalarGrid& input, double iso_value, const IsoSurfaceOptions& options) {
  require_input(std::isfinite(iso_value), "iso-surface", "iso value", "is not finite");
  require_input(options.keep_largest_components >= 0, "iso-surface", "keep_largest_components", "is negative");
  input.validate("iso-surface grid");
  const ScalarGrid resampled =
      options.resample_factor != 1.0 ? resample_grid(input, options.resample_factor) : ScalarGrid{};
  const ScalarGrid& grid = options.resample_factor != 1.0 ? resampled : input;

  // OpenVDB meshes level sets: negative inside. Store f = iso - v so values above the iso-value are inside, and
  // use a positive background (outside) so the border is closed.
  const auto [lo, hi] = grid.value_range();
  if (!(double(hi) > iso_value)) return TriMesh{};
  const double span = std::max(1.0, double(hi) - double(lo));
  const float background = static_cast<float>(std::max(iso_value - double(lo), 1e-3 * span));

  const float nudge = static_cast<float>(1e-4 * span);
  openvdb::initialize();
  std::vector<float> shifted(grid.values.size());
  for (std::size_t i = 0; i < shifted.size(); ++i) {
    const float v = grid.values[i];
    const float f = static_cast<float>(iso_value - double(v));
    if (std::isnan(v)) {
      shifted[i] = background;  // missing samples are outside
    } else if (!std::isfinite(f)) {
      shifted[i] = f > 0.0f ? background : -background;  // +-inf samples: clamp so interpolation stays finite
    } else {
      shifted[i] = f == 0.0f ? nudge : f;
    }
  }
  const openvdb::CoordBBox box(openvdb::Coord(0, 0, 0), openvdb::Coord(grid.nx - 1, grid.ny - 1, grid.nz - 1));
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, shifted.data());
  openvdb::FloatGrid::Ptr vdb = openvdb::FloatGrid::create(background);
  openvdb::tools::copyFromDense(dense, *vdb, 0.0f);
  std::vector<float>().swap(shifted);

  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*vdb, points, triangles, quads, 0.0, 0.0, false);
  vdb.reset();

  const Mat3 m = grid.index_to_world_matrix();
  std::vector<Vec3> positions;
  positions.reserve(points.size());
  for (const auto& p : points) positions.push_back(grid.origin + m * Vec3(p.x(), p.y(), p.z()));
  // OpenVDB's polygons are counter-clockwise seen from the positive (here: outside) side in index space; reverse
  // them when the index-to-world map is a reflection.
  TriMesh mesh = mesh_from_vdb_polygons(std::move(positions), triangles, quads, m.determinant() < 0.0);
  if (options.keep_largest_components > 0) mesh = keep_largest_components(mesh, options.keep_largest_components);
  if (options.smoothing_iterations > 0) {
    taubin_smooth(mesh, options.smoothing_iterations, options.smoothing_lambda, options.smoothing_mu);
  }
  compute_normals(mesh);
  return mesh;
}

}  // namespace forensim
