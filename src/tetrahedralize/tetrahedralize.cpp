// False positives of -Wnull-dereference inside the standard library, Boost and CGAL containers after inlining:
// the warning is reported at header locations, so it is disabled before any include.
#pragma GCC diagnostic ignored "-Wnull-dereference"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // likewise, in std::pair inside CGAL at -O1 (sanitizer builds)

#include "tetrahedralize/tetrahedralize.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_polyhedron_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedral_complex_mesh_domain_3.h>
#include <CGAL/Random.h>
#include <CGAL/exude_mesh_3.h>
#include <CGAL/refine_mesh_3.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <thread>
#include <unordered_map>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "core/timer.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "mesh_processing/remove_self_intersections.hpp"
#include "mesh_processing/repair_mesh.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/self_intersection.hpp"
#include "spatial/winding_number.hpp"
#include "volume/iso_surface.hpp"
#include "volume/offset_surface.hpp"

namespace forensim {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Mesh_polyhedron_3<Kernel>::type;
using Domain = CGAL::Polyhedral_complex_mesh_domain_3<Kernel, Polyhedron>;
using Triangulation = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using Complex = CGAL::Mesh_complex_3_in_triangulation_3<Triangulation>;
using Criteria = CGAL::Mesh_criteria_3<Triangulation>;
using Point = Kernel::Point_3;

// Subdomain labels of the implicit domain (0 is outside).
constexpr int domain_flesh = 1;
constexpr int domain_bone = 2;

Polyhedron to_polyhedron(const TriMesh& mesh) {
  std::vector<Point> points;
  points.reserve(mesh.positions.size());
  for (const Vec3& x : mesh.positions) points.emplace_back(x.x(), x.y(), x.z());
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(mesh.triangles.size());
  for (const Tri& t : mesh.triangles) {
    faces.push_back({static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
  }
  Polyhedron polyhedron;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, polyhedron);
  return polyhedron;
}

struct MeshPass {
  TetMesh mesh;
  double seconds = 0.0;
  bool exude_cut_short = false;  ///< the sliver exudation reached its time bound
};

/// Sets `stop` once `limit_s` seconds have passed (then `timed_out` too) or the user asked to stop, polling
/// every 50 ms; destroying it ends the thread.
class RefinementWatchdog {
 public:
  explicit RefinementWatchdog(double limit_s)
      : m_thread([this, limit_s](std::stop_token token) {
          const auto start = std::chrono::steady_clock::now();
          while (!token.stop_requested()) {
            if (interrupt_requested()) {
              stop.store(true, std::memory_order_release);
              return;
            }
            const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (elapsed > limit_s) {
              timed_out.store(true);
              stop.store(true, std::memory_order_release);
              return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
          }
        }) {}
  std::atomic<bool> stop{false};
  std::atomic<bool> timed_out{false};

 private:
  std::jthread m_thread;  // last: starts after the flags exist, joins before they go
};

/// One Mesh_3 refinement of `domain` with criteria for `edge` mm, bounded at `node_limit` nodes and
/// `time_limit_s` seconds, seeded on `surfaces`.
MeshPass refine_domain(const Domain& domain, const std::vector<const TriMesh*>& surfaces, double edge,
                       std::size_t node_limit, double time_limit_s, const TetrahedralizeOptions& o) {
  Stopwatch watch;
  namespace p = CGAL::parameters;
  // Cell size bound is a circumradius: sqrt(6)/4 of the edge for a regular tet.
  const double cell_size = 0.612 * edge * o.interior_size_factor;
  Criteria criteria(p::facet_angle = o.facet_angle_deg, p::facet_size = edge,
                    p::facet_distance = std::max(o.surface_distance_fraction * edge, o.min_surface_distance_mm),
                    p::cell_radius_edge_ratio = o.radius_edge_bound, p::cell_size = cell_size);

  // Seed every surface (skin and each bone component) with points, so no bone is missed by the random
  // initial rays Mesh_3 would shoot from the domain's centre.
  Complex complex;
  Triangulation& tr = complex.triangulation();
  auto construct_intersection = domain.construct_intersection_object();
  for (const TriMesh* surface : surfaces) {
    const std::vector<Vec3> normals = vertex_normals(*surface);
    int components = 0;
    const std::vector<int> component = triangle_components(*surface, &components);
    std::vector<int> seeded(static_cast<std::size_t>(components), 0);
    const std::size_t stride = std::max<std::size_t>(1, surface->triangle_count() / 400);
    for (std::size_t t = 0; t < surface->triangle_count(); t += stride) {
      int& count = seeded[static_cast<std::size_t>(component[t])];
      if (count >= 24) continue;
      const Index v = surface->triangles[t][0];
      const Vec3& x = surface->positions[static_cast<std::size_t>(v)];
      const Vec3& n = normals[static_cast<std::size_t>(v)];
      const double h = 0.25 * edge;
      const Vec3 a = x - h * n, b = x + h * n;
      const auto hit =
          construct_intersection(Kernel::Segment_3(Point(a.x(), a.y(), a.z()), Point(b.x(), b.y(), b.z())));
      if (std::get<2>(hit) == 0) continue;
      const auto vertex = tr.insert(Triangulation::Weighted_point(std::get<0>(hit)));
      if (vertex == Triangulation::Vertex_handle()) continue;
      complex.set_dimension(vertex, 2);
      complex.set_index(vertex, std::get<1>(hit));
      ++count;
    }
  }
  if (tr.dimension() != 3) {
    throw InputError("skin surface", "",
                     "too small or too thin to mesh at an edge length of " + std::to_string(edge) + " mm");
  }
  // The manifold criterion keeps the boundary a closed 2-manifold; surfaces with near-contacts (CT skulls at
  // a few voxels' thickness) can need it off.
  const auto manifold = o.manifold_boundary ? p::manifold() : p::non_manifold();
  // Refinement stops at max_nodes (Mesh_3's maximal_number_of_vertices) instead of filling the memory: the
  // manifold criterion can refine without end near self-contacts of a scan.
  // It also stops at the time bound or on an interruption: a watchdog sets the flag Mesher_3 polls between
  // insertions (CGAL_MESH_3_STOPPED).
  CGAL::Mesh_error_code error = CGAL::CGAL_MESH_3_NO_ERROR;
  {
    RefinementWatchdog watchdog(time_limit_s);
    const auto limits = p::mesh_3_options(p::maximal_number_of_vertices = node_limit, p::pointer_to_error_code = &error,
                                          p::pointer_to_stop_atomic_boolean = &watchdog.stop);
    if (o.perturb) {
      CGAL::refine_mesh_3(complex, domain, criteria, manifold, p::no_lloyd(), p::no_odt(),
                          p::perturb(p::time_limit = 0, p::sliver_bound = o.min_dihedral_deg), p::no_exude(), limits);
    } else {
      CGAL::refine_mesh_3(complex, domain, criteria, manifold, p::no_lloyd(), p::no_odt(), p::no_perturb(),
                          p::no_exude(), limits);
    }
    if (error == CGAL::CGAL_MESH_3_STOPPED && !watchdog.timed_out.load()) {
      throw CancelledError("tetrahedralize: interrupted during the mesh refinement");
    }
  }
  const char* touching_hint =
      "; surfaces that touch or nearly touch themselves or each other (lips, ears, eyelids of a scan; two parts "
      "sharing an edge or a corner) keep the manifold criterion refining: turn it off (manifold_boundary, "
      "--non-manifold), or give a coarser surface distance";
  if (error == CGAL::CGAL_MESH_3_MAXIMAL_NUMBER_OF_VERTICES_REACHED) {
    throw InputError("skin surface", "",
                     "the mesher reached its limit of " + std::to_string(node_limit) + " nodes at an edge length of " +
                         std::to_string(edge) + " mm before the surfaces were resolved" + touching_hint);
  }
  if (error == CGAL::CGAL_MESH_3_STOPPED) {
    char line[160];
    std::snprintf(line, sizeof line, "the mesh refinement did not finish within its bound of %.0f s (%zu nodes so far)",
                  time_limit_s, static_cast<std::size_t>(tr.number_of_vertices()));
    throw InputError("skin surface", "", line + std::string(touching_hint) + ", or raise the bound (time_limit_s)");
  }

  MeshPass pass;
  if (error == CGAL::CGAL_MESH_3_NO_ERROR) {
    // Exudation last, as refine_mesh_3 would run it, but bounded in time: on some inputs CGAL's exuder keeps
    // pumping the same slivers (its queue orders equal cells by address, so whether it does changes with the
    // process's heap; CGAL issue #8775), growing without end. A normal run takes a fraction of the
    // refinement's time; the bound is ten times that, and at least a minute.
    const double limit = std::max(60.0, 10.0 * watch.seconds());
    const CGAL::Mesh_optimization_return_code code =
        CGAL::exude_mesh_3(complex, p::time_limit = limit, p::sliver_bound = o.min_dihedral_deg);
    pass.exude_cut_short = code == CGAL::TIME_LIMIT_REACHED;
  }
  std::unordered_map<Triangulation::Vertex_handle, Index> node_of;
  for (auto cell = complex.cells_in_complex_begin(); cell != complex.cells_in_complex_end(); ++cell) {
    Tet tet{};
    Vec3 corner[4];
    for (int i = 0; i < 4; ++i) {
      const auto vh = cell->vertex(i);
      auto found = node_of.find(vh);
      if (found == node_of.end()) {
        const Point& q = tr.point(vh).point();
        found = node_of.emplace(vh, static_cast<Index>(pass.mesh.positions.size())).first;
        pass.mesh.positions.emplace_back(q.x(), q.y(), q.z());
      }
      tet[static_cast<std::size_t>(i)] = found->second;
      corner[i] = pass.mesh.positions[static_cast<std::size_t>(found->second)];
    }
    const double volume = tet_signed_volume(corner[0], corner[1], corner[2], corner[3]);
    if (volume == 0.0) continue;
    if (volume < 0.0) std::swap(tet[2], tet[3]);
    pass.mesh.tets.push_back(tet);
    pass.mesh.tet_labels.push_back(complex.subdomain_index(cell) == domain_bone ? tissue_bone : tissue_flesh);
  }
  pass.seconds = watch.seconds();
  return pass;
}

/// One Mesh_3 run with criteria for `edge` mm, bounded at `node_limit` nodes and `time_limit_s` seconds of
/// refinement.
MeshPass mesh_once(const TriMesh& skin, const std::vector<TriMesh>& bones, double edge, std::size_t node_limit,
                   double time_limit_s, const TetrahedralizeOptions& o) {
  CGAL::Random rng(o.seed);
  // Patches: the skin separates flesh (inside) from the outside (0), each bone separates bone (inside) from
  // flesh; pairs are (inside, outside) as the domain's ray-shooting Is_in_domain reads them.
  std::vector<Polyhedron> patches{to_polyhedron(skin)};
  std::vector<std::pair<int, int>> sides{{domain_flesh, 0}};
  std::vector<const TriMesh*> surfaces{&skin};
  for (const TriMesh& bone : bones) {
    patches.push_back(to_polyhedron(bone));
    sides.emplace_back(domain_bone, domain_flesh);
    surfaces.push_back(&bone);
  }
  const Domain domain(patches.begin(), patches.end(), sides.begin(), sides.end(), &rng);
  return refine_domain(domain, surfaces, edge, node_limit, time_limit_s, o);
}

TriMesh joined(const TriMesh& a, const TriMesh& b) {
  TriMesh out;
  out.positions = a.positions;
  out.positions.insert(out.positions.end(), b.positions.begin(), b.positions.end());
  out.triangles = a.triangles;
  const auto offset = static_cast<Index>(a.positions.size());
  for (const Tri& t : b.triangles) out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return out;
}

/// Mesh_3's polyhedral complex domain samples the patches as they are and assumes embedded patches that do
/// not cross (its in/out tests by ray parity disagree otherwise, and the triangulation it builds can be left
/// inconsistent): refuse a bone that passes through the skin or another bone, naming it. Each surface is
/// embedded already (closed_body_surface()).
void require_embedded_patches(const TriMesh& skin, const std::vector<TriMesh>& bones,
                              const std::vector<std::string>& bone_names) {
  const auto refuse = [](const std::string& name, std::size_t crossings, const std::string& what) {
    throw InputError(name, "",
                     std::to_string(crossings) + " of its edges cross " + what +
                         " (or theirs cross it); the mesher needs surfaces that do not pass through each other");
  };
  for (std::size_t i = 0; i < bones.size(); ++i) {
    const std::size_t both = self_intersection_count(joined(skin, bones[i]));
    if (both > 0) refuse(bone_names[i], both, "the skin surface's triangles");
    for (std::size_t j = i + 1; j < bones.size(); ++j) {
      const std::size_t pair = self_intersection_count(joined(bones[i], bones[j]));
      if (pair > 0) refuse(bone_names[j], pair, bone_names[i] + "'s triangles");
    }
  }
}

/// Moves the vertices of `bone` that lie outside `skin` or nearer to it than `clearance` (mm) to that depth
/// below the skin's closest point, a few rounds (a moved vertex can pull its triangles across). Where the
/// soft tissue is thinner than a voxel (a CT's forehead), the separately smoothed bone and skin iso-surfaces
/// cross; the mesher needs them apart.
void keep_inside(TriMesh& bone, const TriMesh& skin, double clearance) {
  if (bone.triangle_count() == 0) return;
  const ClosestPointQuery closest(skin);
  const WindingNumber winding(skin);
  const std::vector<Vec3> skin_normals = vertex_normals(skin);
  for (int round = 0; round < 4; ++round) {
    const std::vector<std::optional<ClosestPoint>> near = closest.query_batch(bone.positions);
    const std::vector<bool> inside = winding.inside_batch(bone.positions);
    std::size_t moved = 0;
    for (std::size_t v = 0; v < bone.positions.size(); ++v) {
      if (!near[v] || (inside[v] && near[v]->distance >= clearance)) continue;
      const Tri& t = skin.triangles[static_cast<std::size_t>(near[v]->triangle)];
      Vec3 n = Vec3::Zero();
      for (int k = 0; k < 3; ++k) n += near[v]->barycentric[k] * skin_normals[static_cast<std::size_t>(t[k])];
      if (!(n.norm() > 0.0)) continue;
      bone.positions[v] = near[v]->point - clearance * n.normalized();
      ++moved;
    }
    if (moved == 0) break;
  }
  bone.normals.clear();
}

std::string format_mm3(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.1f cm^3", v / 1000.0);
  return text;
}

}  // namespace

std::string TetrahedralizeReport::summary() const {
  char line[512];
  std::string out;
  std::snprintf(line, sizeof line, "%zu nodes, %zu tets (%zu bone) at edge %.2f mm, %d pass%s\n", node_count, tet_count,
                bone_tet_count, edge_length_mm, passes, passes == 1 ? "" : "es");
  out += line;
  const auto percent = [](double a, double b) { return b == 0.0 ? 0.0 : 100.0 * (a - b) / b; };
  out += "volume: tets " + format_mm3(tet_volume_mm3) + ", skin surface " + format_mm3(skin_volume_mm3);
  std::snprintf(line, sizeof line, " (%+.2f %%)\n", percent(tet_volume_mm3, skin_volume_mm3));
  out += line;
  out += "bone: tets " + format_mm3(bone_tet_volume_mm3) + ", bone surfaces " + format_mm3(bone_volume_mm3);
  std::snprintf(line, sizeof line, " (%+.2f %%)\n", percent(bone_tet_volume_mm3, bone_volume_mm3));
  out += line;
  std::snprintf(line, sizeof line, "time: prepare %.2f s, mesh %.2f s\n", seconds_prepare, seconds_mesh);
  out += line;
  for (const std::string& note : notes) out += "note: " + note + "\n";
  return out;
}

TriMesh closed_body_surface(const TriMesh& input, const std::string& name, bool close_openings,
                            std::vector<std::string>& notes) {
  input.validate(name);
  require_input(input.triangle_count() > 0, name, "", "the surface is empty (no triangles)");
  TriMesh mesh;
  mesh.positions = input.positions;
  mesh.triangles = input.triangles;
  const TopologyReport topology = check_topology(mesh);
  if (!topology.is_closed() || !topology.is_manifold() || !topology.is_oriented() ||
      topology.degenerate_triangle_count > 0) {
    // Scan artefacts are small; an opening a quarter of the surface's size is a cut, not a hole to guess.
    RepairOptions repair;
    repair.max_hole_edges = 500;
    repair.max_hole_diameter = close_openings ? 0.0 : 0.25 * bounding_box(mesh.positions).diagonal();
    if (close_openings) repair.max_hole_edges = 0;
    const RepairReport done = repair_mesh(mesh, repair);
    if (!done.closed() || !done.manifold()) {
      std::string hint;
      if (done.holes_skipped > 0) {
        hint = "; " + std::to_string(done.holes_skipped) +
               " opening(s) span more than a quarter of the surface's size (a cut, such as a bust's base, not a "
               "scan hole): cap them, or let forensim close them (close_openings, --close-openings)";
      }
      throw InputError(name, "",
                       "the surface is not closed and could not be repaired (" + topology.summary() +
                           "; after repair: " + done.after.summary() + ")" + hint);
    }
    notes.push_back(name + " repaired: " + topology.summary() + " -> " + done.after.summary());
  }
  // The mesher needs an embedded surface: scans pass through themselves where thin parts press together.
  if (self_intersection_count(mesh) > 0) {
    const SelfIntersectionRepair fixed = remove_self_intersections(mesh, name);
    if (!fixed.embedded()) {
      throw InputError(name, "",
                       "the surface passes through itself (" + std::to_string(fixed.intersecting_pairs_before) +
                           " pairs of crossing triangles) and removing the crossings failed (" +
                           std::to_string(fixed.intersecting_pairs_after) + " pairs remain)");
    }
    notes.push_back(name + " passed through itself (" + std::to_string(fixed.intersecting_pairs_before) +
                    " pairs of crossing triangles): the crossing triangles were replaced by smooth patches (" +
                    std::to_string(fixed.triangles_before) + " -> " + std::to_string(fixed.triangles_after) +
                    " triangles)");
  }
  double volume = enclosed_volume(mesh);
  if (volume < 0.0) {
    for (Tri& t : mesh.triangles) std::swap(t[1], t[2]);
    volume = -volume;
    notes.push_back(name + " was oriented inward; flipped");
  }
  require_input(volume > 0.0, name, "", "the surface encloses no volume");
  return mesh;
}

TetMesh tetrahedralize(const TriMesh& skin_input, const std::vector<TriMesh>& bone_inputs,
                       const TetrahedralizeOptions& options, TetrahedralizeReport* report) {
  Stopwatch watch;
  TetrahedralizeReport local;
  TetrahedralizeReport& r = report ? *report : local;
  r = TetrahedralizeReport{};
  require_input(options.edge_length_mm >= 0.0 && std::isfinite(options.edge_length_mm), "tetrahedralize options",
                "edge_length_mm", "must be a finite length >= 0");
  require_input(options.edge_length_mm > 0.0 || options.target_nodes > 0 || options.target_tets > 0,
                "tetrahedralize options", "", "give an edge length, a node count or a tet count");
  require_input(options.initial_edge_mm >= 0.0 && std::isfinite(options.initial_edge_mm), "tetrahedralize options",
                "initial_edge_mm", "must be a finite length >= 0");
  require_input(options.interior_size_factor >= 0.25 && options.interior_size_factor <= 16.0, "tetrahedralize options",
                "interior_size_factor", "must be in [0.25, 16]");
  require_input(options.radius_edge_bound >= 1.0, "tetrahedralize options", "radius_edge_bound", "must be >= 1");
  require_input(options.surface_distance_fraction > 0.0 && options.surface_distance_fraction <= 1.0,
                "tetrahedralize options", "surface_distance_fraction", "must be in (0, 1]");
  require_input(options.facet_angle_deg > 0.0 && options.facet_angle_deg <= 30.0, "tetrahedralize options",
                "facet_angle_deg", "must be in (0, 30]");

  const TriMesh skin = closed_body_surface(skin_input, "skin surface", options.close_openings, r.notes);
  r.skin_volume_mm3 = enclosed_volume(skin);
  auto skin_winding = std::make_shared<const WindingNumber>(skin);
  std::vector<TriMesh> bones;
  require_input(options.max_nodes >= 100, "tetrahedralize options", "max_nodes", "must be at least 100");
  require_input(std::isfinite(options.time_limit_s) && options.time_limit_s >= 0.0, "tetrahedralize options",
                "time_limit_s", "must be a finite number of seconds >= 0");
  require_input(std::isfinite(options.bone_offset_mm) && options.bone_offset_mm >= 0.0, "tetrahedralize options",
                "bone_offset_mm", "must be a finite depth >= 0");
  if (options.bone_offset_mm > 0.0 && bone_inputs.empty()) {
    InnerOffsetOptions offset;
    offset.depth_mm = options.bone_offset_mm;
    bones.push_back(inner_offset_surface(skin, offset, "skin surface"));
    r.bone_volume_mm3 = enclosed_volume(bones.back());
    char note[160];
    std::snprintf(note, sizeof note, "bone: the skin's inner offset surface %.1f mm deep (%zu triangles)",
                  options.bone_offset_mm, bones.back().triangle_count());
    r.notes.emplace_back(note);
  }
  for (std::size_t i = 0; i < bone_inputs.size(); ++i) {
    const std::string name = "bone surface " + std::to_string(i);
    TriMesh bone = closed_body_surface(bone_inputs[i], name, options.close_openings, r.notes);
    const std::vector<bool> inside = skin_winding->inside_batch(bone.positions);
    const auto outside = static_cast<std::size_t>(std::count(inside.begin(), inside.end(), false));
    if (outside > 0) {
      throw InputError(name,
                       "vertex " + std::to_string(std::find(inside.begin(), inside.end(), false) - inside.begin()),
                       std::to_string(outside) + " of " + std::to_string(bone.vertex_count()) +
                           " vertices lie outside the skin surface; bones must lie inside the skin");
    }
    r.bone_volume_mm3 += enclosed_volume(bone);
    bones.push_back(std::move(bone));
  }
  // Bones must not overlap each other (their surfaces would cross).
  for (std::size_t i = 0; i < bones.size(); ++i) {
    const WindingNumber winding(bones[i]);
    for (std::size_t j = 0; j < bones.size(); ++j) {
      if (j == i) continue;
      const std::vector<bool> inside = winding.inside_batch(bones[j].positions);
      const auto overlap = std::find(inside.begin(), inside.end(), true);
      if (overlap != inside.end()) {
        throw InputError("bone surface " + std::to_string(j), "vertex " + std::to_string(overlap - inside.begin()),
                         "lies inside bone surface " + std::to_string(i) + "; bones must not overlap");
      }
    }
  }
  std::vector<std::string> bone_names;
  for (std::size_t i = 0; i < bones.size(); ++i) {
    bone_names.push_back(bone_inputs.empty() ? "the skin's inner offset surface (bone)"
                                             : "bone surface " + std::to_string(i));
  }
  require_embedded_patches(skin, bones, bone_names);
  r.seconds_prepare = watch.seconds();

  // Edge length: given, or from the count target. A Mesh_3 mesh of edge h has about V / (0.1 h^3) tets and
  // a sixth as many nodes (measured on the phantoms); a second pass corrects the estimate.
  double edge = options.edge_length_mm;
  const bool by_count = edge <= 0.0;
  const double target =
      options.target_nodes > 0 ? static_cast<double>(options.target_nodes) : static_cast<double>(options.target_tets);
  const double per_tet = options.target_nodes > 0 ? 1.0 / 5.0 : 1.0;
  if (by_count) {
    edge = options.initial_edge_mm > 0.0 ? options.initial_edge_mm
                                         : std::cbrt(r.skin_volume_mm3 * per_tet / (0.1 * target));
  }
  // Bounds of each pass: nodes (50 times the estimate for its edge length, at least 100,000, at most
  // max_nodes) and seconds (time_limit_s, or 300 s plus 1 s per 2,000 expected nodes).
  const auto run_pass = [&](double h) {
    const double expected = r.skin_volume_mm3 / (0.5 * h * h * h);
    const double nodes = std::min(std::max(50.0 * expected, 1e5), static_cast<double>(options.max_nodes));
    const double seconds = options.time_limit_s > 0.0 ? options.time_limit_s : 300.0 + expected / 2000.0;
    return mesh_once(skin, bones, h, static_cast<std::size_t>(nodes), seconds, options);
  };
  MeshPass pass = run_pass(edge);
  r.passes = 1;
  if (by_count) {
    // Counts fall between h^-2 (surface-dominated) and h^-3 (volume-dominated): start from an exponent of 2.5,
    // then take secant steps on log(count) against log(edge) (at most four passes in all).
    auto count_of = [&](const MeshPass& mp) {
      return options.target_nodes > 0 ? static_cast<double>(mp.mesh.vertex_count())
                                      : static_cast<double>(mp.mesh.tet_count());
    };
    double exponent = 2.5;
    double got = count_of(pass);
    double total_seconds = pass.seconds;
    while (got > 0.0 && std::abs(got - target) > options.count_tolerance * target && r.passes < 4) {
      const double previous_edge = edge, previous_got = got;
      edge *= std::pow(got / target, 1.0 / exponent);
      pass = run_pass(edge);
      total_seconds += pass.seconds;
      ++r.passes;
      got = count_of(pass);
      const double measured = std::log(got / previous_got) / std::log(previous_edge / edge);
      if (std::isfinite(measured) && measured > 1.0 && measured < 4.0) exponent = measured;
    }
    pass.seconds = total_seconds;
  }
  require_input(pass.mesh.tet_count() > 0, "skin surface", "",
                "no tets were produced at an edge length of " + std::to_string(edge) + " mm");
  if (pass.exude_cut_short) {
    r.notes.emplace_back(
        "the sliver exudation was stopped at its time bound (CGAL's exuder kept pumping the same "
        "slivers); some slivers may remain");
  }
  r.edge_length_mm = edge;
  r.seconds_mesh = pass.seconds;
  r.node_count = pass.mesh.vertex_count();
  r.tet_count = pass.mesh.tet_count();
  r.bone_tet_count =
      static_cast<std::size_t>(std::count(pass.mesh.tet_labels.begin(), pass.mesh.tet_labels.end(), tissue_bone));
  r.tet_volume_mm3 = tet_mesh_volume(pass.mesh);
  r.bone_tet_volume_mm3 = tet_mesh_volume(pass.mesh, tissue_bone);
  return std::move(pass.mesh);
}

CtBodySurfaces ct_body_surfaces(const ScalarGrid& grid, double skin_iso, double bone_iso) {
  require_input(std::isfinite(skin_iso) && std::isfinite(bone_iso) && bone_iso > skin_iso, "CT iso-values", "",
                "need finite iso-values with bone above skin");
  // Marching-cubes surfaces carry voxel staircases: smooth them (Taubin keeps the volume) and do not ask the
  // mesher to follow them closer than a quarter voxel.
  IsoSurfaceOptions iso;
  iso.keep_largest_components = 1;
  iso.smoothing_iterations = 10;
  TriMesh skin = extract_iso_surface(grid, skin_iso, iso);
  require_input(skin.triangle_count() > 0, "CT volume", "skin iso-value " + std::to_string(skin_iso),
                "no sample lies above the skin iso-value");
  iso.keep_largest_components = 0;
  const TriMesh bone_all = extract_iso_surface(grid, bone_iso, iso);
  CtBodySurfaces out;
  std::vector<TriMesh>& bones = out.bones;
  if (bone_all.triangle_count() > 0) {
    // Keep the bone components that lie entirely inside the skin and enclose a positive volume (inner
    // shells of hollow bones are part of the component set of their outer shell's volume only when nested;
    // they are kept together so the winding number handles cavities).
    const WindingNumber skin_winding(skin);
    const std::vector<bool> inside = skin_winding.inside_batch(bone_all.positions);
    std::vector<bool> keep(bone_all.triangle_count(), false);
    int components = 0;
    const std::vector<int> component = triangle_components(bone_all, &components);
    std::vector<char> component_ok(static_cast<std::size_t>(components), 1);
    for (std::size_t t = 0; t < bone_all.triangle_count(); ++t) {
      for (Index v : bone_all.triangles[t]) {
        if (!inside[static_cast<std::size_t>(v)]) component_ok[static_cast<std::size_t>(component[t])] = 0;
      }
    }
    for (std::size_t t = 0; t < bone_all.triangle_count(); ++t)
      keep[t] = component_ok[static_cast<std::size_t>(component[t])] != 0;
    // Specks of bone-dense noise (and tiny ossicles) would only force refinement: keep components enclosing at
    // least 0.5 % of the largest one's volume.
    std::vector<double> component_volume(static_cast<std::size_t>(components), 0.0);
    for (std::size_t t = 0; t < bone_all.triangle_count(); ++t) {
      const Tri& tri = bone_all.triangles[t];
      component_volume[static_cast<std::size_t>(component[t])] +=
          bone_all.positions[static_cast<std::size_t>(tri[0])].dot(
              bone_all.positions[static_cast<std::size_t>(tri[1])].cross(
                  bone_all.positions[static_cast<std::size_t>(tri[2])])) /
          6.0;
    }
    const double largest = *std::max_element(component_volume.begin(), component_volume.end());
    for (std::size_t t = 0; t < bone_all.triangle_count(); ++t)
      keep[t] = keep[t] && std::abs(component_volume[static_cast<std::size_t>(component[t])]) >= 0.005 * largest;
    TriMesh bone = extract_triangles(bone_all, keep);
    keep_inside(bone, skin, 0.5 * grid.spacing.minCoeff());
    if (bone.triangle_count() > 0 && enclosed_volume(bone) > 0.0) bones.push_back(std::move(bone));
  }
  out.skin = std::move(skin);
  return out;
}

TetMesh tetrahedralize_ct(const ScalarGrid& grid, double skin_iso, double bone_iso,
                          const TetrahedralizeOptions& options, TetrahedralizeReport* report) {
  const CtBodySurfaces surfaces = ct_body_surfaces(grid, skin_iso, bone_iso);
  // CT skulls are a few voxels thick and their iso-surfaces nearly touch themselves: Mesh_3's manifold
  // criterion then refines without bound (measured on headsq: out of memory at 12 GB), while without it the
  // same skull meshes in seconds. Nor is the boundary asked to follow the surfaces closer than half a voxel.
  TetrahedralizeOptions ct_options = options;
  ct_options.manifold_boundary = false;
  ct_options.min_surface_distance_mm = std::max(options.min_surface_distance_mm, 0.5 * grid.spacing.minCoeff());
  return tetrahedralize(surfaces.skin, surfaces.bones, ct_options, report);
}

}  // namespace forensim
