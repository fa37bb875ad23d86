#include "craniofacial/skull_completion.hpp"

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"

namespace forensim {

SkullCompletion complete_skull(const TriMesh& scan, const ScanFieldOfView& view, const TriMesh& reference,
                               const SkullRegistration& registration) {
  require_input(!scan.triangles.empty(), "scan skull", "", "the mesh has no triangles");
  require_input(!reference.triangles.empty(), "reference skull", "", "the mesh has no triangles");
  SkullCompletion out;
  if (!view.bounded()) {
    out.mesh = scan;
    out.scan_triangles = scan.triangles.size();
    return out;
  }
  TriMesh& mesh = out.mesh;
  const std::vector<char> cap = view.cap_triangles(scan);
  // The scan without its caps, vertices renumbered.
  std::vector<Index> remap(scan.positions.size(), -1);
  for (std::size_t t = 0; t < scan.triangles.size(); ++t) {
    if (cap[t]) {
      ++out.cap_triangles;
      continue;
    }
    Tri f;
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(scan.triangles[t][static_cast<std::size_t>(k)]);
      if (remap[v] < 0) {
        remap[v] = static_cast<Index>(mesh.positions.size());
        mesh.positions.push_back(scan.positions[v]);
      }
      f[static_cast<std::size_t>(k)] = remap[v];
    }
    mesh.triangles.push_back(f);
    ++out.scan_triangles;
  }
  // The reference's triangles the scan did not see.
  std::vector<Vec3> mapped(reference.positions.size());
  parallel_for(0, mapped.size(), [&](std::size_t i) { mapped[i] = registration.map(reference.positions[i]); });
  std::vector<Index> added(reference.positions.size(), -1);
  for (const Tri& t : reference.triangles) {
    bool outside = true;
    for (Index v : t) outside = outside && !view.contains(mapped[static_cast<std::size_t>(v)]);
    if (!outside) continue;
    Tri f;
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(t[static_cast<std::size_t>(k)]);
      if (added[v] < 0) {
        added[v] = static_cast<Index>(mesh.positions.size());
        mesh.positions.push_back(mapped[v]);
      }
      f[static_cast<std::size_t>(k)] = added[v];
    }
    mesh.triangles.push_back(f);
    ++out.reference_triangles;
  }
  // A reflecting registration would turn the reference inside out.
  if (registration.similarity.rotation.determinant() < 0.0) {
    for (std::size_t t = mesh.triangles.size() - out.reference_triangles; t < mesh.triangles.size(); ++t) {
      std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
    }
  }
  compute_normals(mesh);
  return out;
}

}  // namespace forensim
