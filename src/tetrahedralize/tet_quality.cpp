// False positives of -Wnull-dereference inside the standard library, Boost and CGAL containers after inlining:
// the warning is reported at header locations, so it is disabled before any include.
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include "tetrahedralize/tet_quality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "geometry/mesh_measures.hpp"

namespace forensim {
namespace {

constexpr double pi = 3.14159265358979323846;

std::string bar_line(const std::string& label, std::size_t count, std::size_t total) {
  const int width =
      total == 0 ? 0 : static_cast<int>(std::lround(40.0 * static_cast<double>(count) / static_cast<double>(total)));
  char head[64];
  std::snprintf(head, sizeof head, "  %-12s %9zu ", label.c_str(), count);
  return std::string(head) + std::string(static_cast<std::size_t>(width), '#') + "\n";
}

}  // namespace

double tet_radius_edge_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  // Circumcentre relative to a: solves 2 [u v w]^T x = [|u|^2 |v|^2 |w|^2].
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double det = u.dot(v.cross(w));
  const double shortest = std::sqrt(std::min({u.squaredNorm(), v.squaredNorm(), w.squaredNorm(), (c - b).squaredNorm(),
                                              (d - b).squaredNorm(), (d - c).squaredNorm()}));
  if (det == 0.0 || shortest == 0.0) return std::numeric_limits<double>::infinity();
  const Vec3 x =
      (u.squaredNorm() * v.cross(w) + v.squaredNorm() * w.cross(u) + w.squaredNorm() * u.cross(v)) / (2.0 * det);
  const double ratio = x.norm() / shortest;
  return std::isfinite(ratio) ? ratio : std::numeric_limits<double>::infinity();
}

double tet_min_dihedral_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 p[4] = {a, b, c, d};
  // Outward-or-inward face normals (consistent sign does not matter: the dihedral angle at the edge shared
  // by faces i and j is pi minus the angle between their outward normals).
  Vec3 n[4];
  for (int f = 0; f < 4; ++f) {
    const Vec3& q0 = p[(f + 1) % 4];
    const Vec3& q1 = p[(f + 2) % 4];
    const Vec3& q2 = p[(f + 3) % 4];
    Vec3 normal = (q1 - q0).cross(q2 - q0);
    // Point the normal away from the opposite vertex.
    if (normal.dot(p[f] - q0) > 0.0) normal = -normal;
    const double length = normal.norm();
    if (length == 0.0) return 0.0;
    n[f] = normal / length;
  }
  double smallest = 180.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      const double cosine = std::clamp(-n[i].dot(n[j]), -1.0, 1.0);
      smallest = std::min(smallest, std::acos(cosine) * 180.0 / pi);
    }
  }
  if (tet_signed_volume(a, b, c, d) == 0.0) return 0.0;
  return smallest;
}

TetQualityReport tet_quality(const TetMesh& mesh) {
  mesh.validate("tet mesh");
  TetQualityReport r;
  r.tet_count = mesh.tet_count();
  r.radius_edge_ratio.resize(r.tet_count);
  r.min_dihedral_deg.resize(r.tet_count);
  double re_sum = 0.0, di_sum = 0.0;
  std::size_t re_n = 0;
  r.radius_edge_min = std::numeric_limits<double>::infinity();
  r.dihedral_min = std::numeric_limits<double>::infinity();
  r.radius_edge_max = 0.0;
  r.dihedral_max = 0.0;
  for (std::size_t t = 0; t < r.tet_count; ++t) {
    const Tet& tet = mesh.tets[t];
    const Vec3& a = mesh.positions[static_cast<std::size_t>(tet[0])];
    const Vec3& b = mesh.positions[static_cast<std::size_t>(tet[1])];
    const Vec3& c = mesh.positions[static_cast<std::size_t>(tet[2])];
    const Vec3& d = mesh.positions[static_cast<std::size_t>(tet[3])];
    const double volume = tet_signed_volume(a, b, c, d);
    const double longest = std::sqrt(std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (d - a).squaredNorm(),
                                               (c - b).squaredNorm(), (d - b).squaredNorm(), (d - c).squaredNorm()}));
    const bool flat = std::abs(volume) <= 1e-12 * longest * longest * longest;
    if (flat) {
      ++r.flat_count;
    } else if (volume < 0.0) {
      ++r.inverted_count;
    }
    const double ratio = flat ? std::numeric_limits<double>::infinity() : tet_radius_edge_ratio(a, b, c, d);
    const double dihedral = flat ? 0.0 : tet_min_dihedral_deg(a, b, c, d);
    r.radius_edge_ratio[t] = ratio;
    r.min_dihedral_deg[t] = dihedral;
    if (std::isfinite(ratio)) {
      r.radius_edge_min = std::min(r.radius_edge_min, ratio);
      r.radius_edge_max = std::max(r.radius_edge_max, ratio);
      re_sum += ratio;
      ++re_n;
    }
    r.dihedral_min = std::min(r.dihedral_min, dihedral);
    r.dihedral_max = std::max(r.dihedral_max, dihedral);
    di_sum += dihedral;
    std::size_t bin = 0;
    while (bin < TetQualityReport::radius_edge_bin_edges.size() &&
           !(ratio <= TetQualityReport::radius_edge_bin_edges[bin])) {
      ++bin;
    }
    ++r.radius_edge_histogram[bin];
    const auto dbin = static_cast<std::size_t>(std::clamp(dihedral / TetQualityReport::dihedral_bin_deg, 0.0,
                                                          static_cast<double>(r.dihedral_histogram.size() - 1)));
    ++r.dihedral_histogram[dbin];
  }
  if (re_n == 0) r.radius_edge_min = r.radius_edge_max = 0.0;
  if (r.tet_count == 0) r.dihedral_min = 0.0;
  r.radius_edge_mean = re_n == 0 ? 0.0 : re_sum / static_cast<double>(re_n);
  r.dihedral_mean = r.tet_count == 0 ? 0.0 : di_sum / static_cast<double>(r.tet_count);
  return r;
}

std::string TetQualityReport::summary() const {
  char line[256];
  std::string out;
  std::snprintf(line, sizeof line, "%zu tets, %zu inverted, %zu flat\n", tet_count, inverted_count, flat_count);
  out += line;
  std::snprintf(line, sizeof line, "radius-edge ratio: min %.3f, mean %.3f, max %.3f (regular tet 0.612)\n",
                radius_edge_min, radius_edge_mean, radius_edge_max);
  out += line;
  for (std::size_t i = 0; i < radius_edge_histogram.size(); ++i) {
    std::string label;
    if (i == 0) {
      std::snprintf(line, sizeof line, "<= %.2f", radius_edge_bin_edges[0]);
    } else if (i < radius_edge_bin_edges.size()) {
      std::snprintf(line, sizeof line, "%.2f-%.2f", radius_edge_bin_edges[i - 1], radius_edge_bin_edges[i]);
    } else {
      std::snprintf(line, sizeof line, "> %.2f", radius_edge_bin_edges.back());
    }
    label = line;
    out += bar_line(label, radius_edge_histogram[i], tet_count);
  }
  std::snprintf(line, sizeof line, "min dihedral angle: min %.2f, mean %.2f, max %.2f deg (regular tet 70.53)\n",
                dihedral_min, dihedral_mean, dihedral_max);
  out += line;
  for (std::size_t i = 0; i < dihedral_histogram.size(); ++i) {
    std::snprintf(line, sizeof line, "%2.0f-%2.0f deg", dihedral_bin_deg * static_cast<double>(i),
                  dihedral_bin_deg * static_cast<double>(i + 1));
    out += bar_line(line, dihedral_histogram[i], tet_count);
  }
  return out;
}

}  // namespace forensim
