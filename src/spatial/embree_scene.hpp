#pragma once
/// Internal to the spatial module (included only by its .cpp files, never by public headers): one Embree 3
/// device and committed scene holding a triangle mesh, shared by RayCaster and ClosestPointQuery.
/// Embree stores vertices in float; to keep float rounding relative to the mesh's own size rather than to
/// its distance from the origin, vertices are stored relative to the bounding-box centre (`shift()`), and
/// every query point must be shifted the same way. Double-precision copies of the mesh are kept for exact
/// refinement of the hits Embree finds.

#include <embree3/rtcore.h>

#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"

namespace forensim {

class EmbreeScene {
 public:
  /// Validates `mesh` (InputError naming `source`) and builds a robust static BVH over its triangles.
  /// `context_filter` enables per-query filter callbacks (used for back/front-face culling).
  EmbreeScene(const TriMesh& mesh, const std::string& source, bool context_filter);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene scene() const { return m_scene; }
  /// Embree coordinates = world coordinates - shift().
  const Vec3& shift() const { return m_shift; }
  /// Half the bounding-box diagonal (mm): the scale of float rounding in Embree's coordinates.
  double extent() const { return m_extent; }
  const std::vector<Vec3>& positions() const { return m_positions; }
  const std::vector<Tri>& triangles() const { return m_triangles; }
  bool empty() const { return m_triangles.empty(); }

 private:
  void build();

  bool m_context_filter = false;
  RTCDevice m_device = nullptr;
  RTCScene m_scene = nullptr;
  Vec3 m_shift = Vec3::Zero();
  double m_extent = 0.0;
  std::vector<Vec3> m_positions;
  std::vector<Tri> m_triangles;
};

}  // namespace forensim
