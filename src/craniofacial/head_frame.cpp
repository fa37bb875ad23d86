#include "craniofacial/head_frame.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/error.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "geometry/bounding_box.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {
namespace {

std::string set_source(const LandmarkSet& set) {
  return set.name().empty() ? std::string("skull landmarks") : "skull landmarks '" + set.name() + "'";
}

/// Positions by canonical name for the landmarks the vocabulary knows.
std::map<std::string, Vec3> canonical_positions(const LandmarkSet& set) {
  const LandmarkVocabulary& v = LandmarkVocabulary::built_in();
  std::map<std::string, Vec3> out;
  for (const Landmark& l : set.landmarks()) {
    const auto ref = v.find(l.name);
    if (!ref) continue;
    if (v.site(*ref).laterality == Laterality::bilateral && ref->side == Side::none) continue;
    out.emplace(v.name(*ref), l.position_mm);
  }
  return out;
}

const Vec3& require(const std::map<std::string, Vec3>& p, const std::string& name, const LandmarkSet& set,
                    const std::string& purpose) {
  const auto it = p.find(name);
  if (it == p.end()) throw InputError(set_source(set), name, "landmark '" + name + "' is needed for " + purpose);
  return it->second;
}

}  // namespace

Plane frankfort_plane(const LandmarkSet& skull_landmarks) {
  const auto p = canonical_positions(skull_landmarks);
  const Vec3& po_l = require(p, "po_L", skull_landmarks, "the Frankfort horizontal");
  const Vec3& po_r = require(p, "po_R", skull_landmarks, "the Frankfort horizontal");
  const auto orbitale = p.count("or_L") ? p.find("or_L") : p.find("or_R");
  if (orbitale == p.end()) {
    throw InputError(set_source(skull_landmarks), "or_L",
                     "landmark 'or_L' (or 'or_R') is needed for the Frankfort horizontal");
  }
  const Vec3& orb = orbitale->second;
  const Vec3 mid = 0.5 * (po_l + po_r);
  const Vec3 left = po_l - po_r;
  const Vec3 anterior = orb - mid;
  Vec3 normal = anterior.cross(left);
  const double scale = left.norm() * anterior.norm();
  if (!(normal.norm() > 1e-6 * scale) || scale <= 0.0) {
    throw InputError(set_source(skull_landmarks), "po_L, po_R, or_L",
                     "porions and orbitale are (nearly) collinear or coincide: no Frankfort plane");
  }
  normal.normalize();
  return Plane{(po_l + po_r + orb) / 3.0, normal};
}

Plane midsagittal_plane(const LandmarkSet& skull_landmarks) {
  const LandmarkVocabulary& v = LandmarkVocabulary::built_in();
  const auto p = canonical_positions(skull_landmarks);
  Vec3 normal_sum = Vec3::Zero();
  std::vector<Vec3> on_plane;
  int pairs = 0;
  for (const LandmarkSite& site : v.sites()) {
    if (site.laterality == Laterality::midline) {
      if (const auto it = p.find(site.abbreviation); it != p.end()) on_plane.push_back(it->second);
      continue;
    }
    const auto l = p.find(site.abbreviation + side_suffix(Side::left));
    const auto r = p.find(site.abbreviation + side_suffix(Side::right));
    if (l == p.end() || r == p.end()) continue;
    const Vec3 d = l->second - r->second;
    if (d.norm() <= 1e-9) continue;
    normal_sum += d.normalized();
    on_plane.push_back(0.5 * (l->second + r->second));
    ++pairs;
  }
  const std::string source = set_source(skull_landmarks);
  if (pairs > 0) {
    Vec3 point = Vec3::Zero();
    for (const Vec3& q : on_plane) point += q;
    point /= static_cast<double>(on_plane.size());
    return Plane{point, normal_sum.normalized()};
  }
  if (on_plane.size() < 3) {
    throw InputError(source, "",
                     "a midsagittal plane needs a bilateral pair (e.g. po_L and po_R) or three midline "
                     "landmarks");
  }
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& q : on_plane) centroid += q;
  centroid /= static_cast<double>(on_plane.size());
  Mat3 scatter = Mat3::Zero();
  for (const Vec3& q : on_plane) scatter += (q - centroid) * (q - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(scatter);
  if (eig.eigenvalues()[1] <= 1e-12 * std::max(1.0, eig.eigenvalues()[2])) {
    throw InputError(source, "", "the midline landmarks are collinear: no midsagittal plane");
  }
  Vec3 normal = eig.eigenvectors().col(0).normalized();
  if (normal.x() < 0.0) normal = -normal;
  return Plane{centroid, normal};
}

SymmetryPlaneFit fit_symmetry_plane(const TriMesh& mesh, const Plane& initial, const SymmetryPlaneOptions& options) {
  if (mesh.triangles.empty()) throw InputError("symmetry plane", "mesh", "has no triangles");
  return fit_symmetry_plane(mesh, ClosestPointQuery(mesh), initial, options);
}

SymmetryPlaneFit fit_symmetry_plane(const TriMesh& mesh, const ClosestPointQuery& query, const Plane& initial,
                                    const SymmetryPlaneOptions& options) {
  if (mesh.triangles.empty()) throw InputError("symmetry plane", "mesh", "has no triangles");
  if (query.triangle_count() != mesh.triangles.size()) {
    throw InputError("symmetry plane", "query", "was not built on this mesh (its triangle count differs)");
  }
  if (!initial.normal.allFinite() || initial.normal.norm() < 1e-12 || !initial.point.allFinite()) {
    throw InputError("symmetry plane", "initial plane", "is not finite or has a zero normal");
  }
  const std::vector<Vec3> normals = face_normals(mesh);
  const std::size_t stride = std::max<std::size_t>(
      1, (mesh.positions.size() + options.max_samples - 1) / std::max<std::size_t>(1, options.max_samples));
  // Samples relative to the initial point keep the normal equations well conditioned far from the origin.
  const Vec3 origin = initial.point;
  std::vector<Vec3> samples;
  for (std::size_t i = 0; i < mesh.positions.size(); i += stride) samples.push_back(mesh.positions[i] - origin);
  const double size = std::max(bounding_box(mesh.positions).diagonal(), 1e-12);

  Vec3 n = initial.normal.normalized();
  double d = 0.0;  // plane: n . x = d in sample coordinates
  struct Pair {
    double error;
    std::size_t i;
    Vec3 c;  // closest mesh point of the mirrored sample
    Vec3 m;  // mesh normal there
  };
  // The closest points of the previous iteration bound the next searches (they lie on the mesh): same answers,
  // found sooner.
  std::vector<Vec3> previous;
  const auto correspondences = [&](const Vec3& normal, double offset) {
    std::vector<Vec3> mirrored(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
      mirrored[i] = samples[i] - 2.0 * (normal.dot(samples[i]) - offset) * normal + origin;
    }
    std::vector<double> bounds(samples.size(), std::numeric_limits<double>::infinity());
    if (previous.size() == samples.size()) {
      for (std::size_t i = 0; i < samples.size(); ++i) bounds[i] = (mirrored[i] - previous[i]).norm();
    }
    const auto hits = query.query_batch_bounded(mirrored, bounds);
    previous.assign(samples.size(), Vec3::Constant(std::numeric_limits<double>::infinity()));
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (hits[i]) previous[i] = hits[i]->point;
    }
    std::vector<Pair> pairs;
    pairs.reserve(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (hits[i]) pairs.push_back({hits[i]->distance, i, hits[i]->point - origin, normals[hits[i]->triangle]});
    }
    std::sort(pairs.begin(), pairs.end(),
              [](const Pair& a, const Pair& b) { return a.error < b.error || (a.error == b.error && a.i < b.i); });
    const std::size_t keep = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::llround(double(pairs.size()) * (1.0 - options.trim_fraction))));
    pairs.resize(std::min(keep, pairs.size()));
    return pairs;
  };
  const auto rms = [](const std::vector<Pair>& pairs) {
    double squared = 0.0;
    for (const Pair& p : pairs) squared += p.error * p.error;
    return pairs.empty() ? 0.0 : std::sqrt(squared / double(pairs.size()));
  };

  SymmetryPlaneFit fit;
  for (int it = 0; it < options.max_iterations; ++it) {
    const std::vector<Pair> pairs = correspondences(n, d);
    fit.iterations = it + 1;
    // Point-to-plane Gauss-Newton step on r_i = m_i . (mirror(v_i) - c_i) over (a, b, delta d), with the normal
    // perturbed as n + a e1 + b e2 and mirror(v) = v - 2 (n . v - d) n.
    const Vec3 e1 = n.unitOrthogonal();
    const Vec3 e2 = n.cross(e1);
    Mat3 jtj = Mat3::Zero();
    Vec3 jtr = Vec3::Zero();
    for (const Pair& p : pairs) {
      const Vec3& v = samples[p.i];
      const double s = n.dot(v) - d;
      const Vec3 mirrored = v - 2.0 * s * n;
      const double r = p.m.dot(mirrored - p.c);
      const double mn = p.m.dot(n);
      const Vec3 j(-2.0 * e1.dot(v) * mn - 2.0 * s * p.m.dot(e1), -2.0 * e2.dot(v) * mn - 2.0 * s * p.m.dot(e2),
                   2.0 * mn);
      jtj += j * j.transpose();
      jtr += j * r;
    }
    const Eigen::LDLT<Mat3> ldlt(jtj);
    if (ldlt.info() != Eigen::Success || !(jtj.norm() > 0.0)) break;
    const Vec3 step = -ldlt.solve(jtr);
    if (!step.allFinite()) break;
    const Vec3 next = (n + step[0] * e1 + step[1] * e2).normalized();
    const double moved = std::abs(step[2]) + size * (next - n).norm();
    n = next;
    d += step[2];
    if (moved < options.tolerance_mm) break;
  }
  const std::vector<Pair> final_pairs = correspondences(n, d);
  fit.rms_mm = rms(final_pairs);
  fit.plane = Plane{origin + d * n, n};
  return fit;
}

Eigen::Affine3d HeadFrame::world_to_head() const {
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  t.linear() = axes.transpose();
  t.translation() = -(axes.transpose() * origin);
  return t;
}

HeadFrame head_frame(const Plane& frankfort, const Plane& midsagittal, const LandmarkSet& skull_landmarks) {
  const auto p = canonical_positions(skull_landmarks);
  const Vec3& po_l = require(p, "po_L", skull_landmarks, "the head frame's origin and left side");
  const Vec3& po_r = require(p, "po_R", skull_landmarks, "the head frame's origin and left side");
  HeadFrame frame;
  frame.frankfort = frankfort;
  frame.midsagittal = midsagittal;
  const Vec3 z = frankfort.normal.normalized();
  Vec3 x = midsagittal.normal - midsagittal.normal.dot(z) * z;
  if (x.norm() < 0.1) {
    throw InputError(set_source(skull_landmarks), "head frame",
                     "the Frankfort and midsagittal planes are nearly parallel");
  }
  x.normalize();
  if (x.dot(po_l - po_r) < 0.0) x = -x;
  const Vec3 y = z.cross(x);
  frame.axes.col(0) = x;
  frame.axes.col(1) = y;
  frame.axes.col(2) = z;
  // The porions' midpoint, moved along x (within the Frankfort plane) onto the midsagittal plane.
  const Vec3 mid = 0.5 * (po_l + po_r);
  frame.origin = mid - (midsagittal.signed_distance(mid) / midsagittal.normal.normalized().dot(x)) * x;
  frame.perpendicularity_deg =
      std::abs(90.0 - std::acos(std::clamp(std::abs(midsagittal.normal.normalized().dot(z)), 0.0, 1.0)) * 180.0 / M_PI);
  return frame;
}

HeadFrame head_frame_from_landmarks(const LandmarkSet& skull_landmarks) {
  return head_frame(frankfort_plane(skull_landmarks), midsagittal_plane(skull_landmarks), skull_landmarks);
}

HeadFrame head_frame_from_skull(const TriMesh& skull, const LandmarkSet& skull_landmarks,
                                const SymmetryPlaneOptions& options, SymmetryPlaneFit* fit) {
  const SymmetryPlaneFit symmetry = fit_symmetry_plane(skull, midsagittal_plane(skull_landmarks), options);
  if (fit != nullptr) *fit = symmetry;
  return head_frame(frankfort_plane(skull_landmarks), symmetry.plane, skull_landmarks);
}

}  // namespace forensim
