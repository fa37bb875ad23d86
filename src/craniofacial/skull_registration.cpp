#include "craniofacial/skull_registration.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/nearest_point.hpp"

namespace forensim {

Eigen::Affine3d Similarity::affine() const {
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  a.linear() = scale * rotation;
  a.translation() = translation;
  return a;
}

namespace {

void check_mesh(const TriMesh& mesh, const std::string& name) {
  require_input(!mesh.triangles.empty(), name, "", "the mesh has no triangles");
  require_input(mesh.positions.size() >= 4, name, "", "the mesh has fewer than 4 vertices");
  mesh.validate(name);
}

/// Every k-th entry of `values` (one per mesh vertex), at most `max_samples`.
std::vector<Vec3> every_kth(const std::vector<Vec3>& values, std::size_t max_samples) {
  const std::size_t n = values.size();
  const std::size_t stride = std::max<std::size_t>(1, (n + max_samples - 1) / std::max<std::size_t>(1, max_samples));
  std::vector<Vec3> samples;
  samples.reserve(n / stride + 1);
  for (std::size_t i = 0; i < n; i += stride) samples.push_back(values[i]);
  return samples;
}

/// Every k-th vertex, at most `max_samples`.
std::vector<Vec3> sample_vertices(const TriMesh& mesh, std::size_t max_samples) {
  return every_kth(mesh.positions, max_samples);
}

struct Moments {
  Vec3 centroid = Vec3::Zero();
  Mat3 covariance = Mat3::Zero();
};

Moments moments(const std::vector<Vec3>& points) {
  Moments m;
  for (const Vec3& p : points) m.centroid += p;
  m.centroid /= static_cast<double>(points.size());
  for (const Vec3& p : points) m.covariance += (p - m.centroid) * (p - m.centroid).transpose();
  m.covariance /= static_cast<double>(points.size());
  return m;
}

/// A surface with face normals for point-to-plane terms and, for the target, its caps (triangles closing a cut).
struct TargetSurface {
  TargetSurface(const TriMesh& mesh, const ScanFieldOfView& view_in)
      : query(mesh), face_normals(mesh.triangles.size()), cap(view_in.cap_triangles(mesh)), view(view_in) {
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
      const Tri& t = mesh.triangles[f];
      const Vec3 n = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
      const double len = n.norm();
      face_normals[f] = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
    }
  }
  ClosestPointQuery query;
  std::vector<Vec3> face_normals;
  std::vector<char> cap;
  ScanFieldOfView view;
};

/// Pairs of moving points x (on the mapped reference) and fixed points q (on the target) with the normal n of
/// the point-to-plane term; pairs not kept carry no weight.
struct Correspondences {
  std::vector<Vec3> moving;
  std::vector<Vec3> fixed;
  std::vector<Vec3> normal;
  std::vector<double> distance;
  std::vector<Vec3> surface_point;  ///< the closest point in the searched mesh's own coordinates
  std::vector<char> valid;          ///< the pair exists (forward: in the target's view, not on a cap)
  std::vector<char> kept;           ///< valid and not trimmed
  double trimmed_rms = 0.0;
  std::size_t kept_count = 0;
};

/// Marks the best valid pairs kept: all but the worst `trim_fraction` of the valid ones. Fills trimmed_rms.
void trim(Correspondences& c, double trim_fraction) {
  const std::size_t n = c.distance.size();
  std::vector<double> sorted;
  sorted.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (c.valid[i]) sorted.push_back(c.distance[i]);
  }
  c.kept.assign(n, 0);
  c.kept_count = 0;
  c.trimmed_rms = 0.0;
  const std::size_t m = sorted.size();
  if (m == 0) return;
  const std::size_t keep = std::max<std::size_t>(
      1, m - std::min(m - 1, static_cast<std::size_t>(std::floor(trim_fraction * static_cast<double>(m)))));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(keep - 1), sorted.end());
  const double threshold = sorted[keep - 1];
  double sum = 0.0;
  for (std::size_t i = 0; i < n && c.kept_count < keep; ++i) {
    if (c.valid[i] && c.distance[i] <= threshold) {
      c.kept[i] = 1;
      sum += c.distance[i] * c.distance[i];
      ++c.kept_count;
    }
  }
  c.trimmed_rms = std::sqrt(sum / static_cast<double>(c.kept_count));
}

/// Closest points of `points` on `surface`; `previous` (pairs of the same points before they moved, or null)
/// bounds each search by the distance to the previous closest point, which lies on the surface: the same
/// answer, found sooner.
std::vector<std::optional<ClosestPoint>> closest_points(const TargetSurface& surface, const std::vector<Vec3>& points,
                                                        const Correspondences* previous) {
  if (!previous || previous->surface_point.size() != points.size()) return surface.query.query_batch(points);
  std::vector<double> bounds(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) bounds[i] = (points[i] - previous->surface_point[i]).norm();
  return surface.query.query_batch_bounded(points, bounds);
}

/// Closest target points of `points`: pairs outside the target's view or onto a cap are invalid, the worst
/// `trim_fraction` of the rest dropped. `previous`: as closest_points.
Correspondences correspond(const TargetSurface& target, const std::vector<Vec3>& points, double trim_fraction,
                           const Correspondences* previous = nullptr) {
  Correspondences c;
  const auto hits = closest_points(target, points, previous);
  const std::size_t n = points.size();
  c.moving = points;
  c.fixed.resize(n);
  c.normal.resize(n);
  c.distance.resize(n);
  c.valid.assign(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const auto f = static_cast<std::size_t>(hits[i]->triangle);
    c.fixed[i] = hits[i]->point;
    c.normal[i] = target.face_normals[f];
    c.distance[i] = hits[i]->distance;
    c.valid[i] = static_cast<char>(!target.cap[f] && target.view.contains(points[i]));
  }
  c.surface_point = c.fixed;
  trim(c, trim_fraction);
  return c;
}

/// Closest points on the mapped reference of the target samples `targets`, found on the unmapped reference
/// (`reference`) through the inverse map; the worst `trim_fraction` dropped.
Correspondences correspond_reverse(const TargetSurface& reference, const Similarity& map,
                                   const std::vector<Vec3>& targets, double trim_fraction,
                                   const Correspondences* previous = nullptr) {
  Correspondences c;
  const std::size_t n = targets.size();
  const Mat3 inverse = map.rotation.transpose() / map.scale;
  std::vector<Vec3> z(n);
  for (std::size_t i = 0; i < n; ++i) z[i] = inverse * (targets[i] - map.translation);
  const auto hits = closest_points(reference, z, previous);
  c.moving.resize(n);
  c.fixed = targets;
  c.normal.resize(n);
  c.distance.resize(n);
  c.valid.assign(n, 1);
  c.surface_point.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    c.surface_point[i] = hits[i]->point;
    c.moving[i] = map.apply(hits[i]->point);
    c.normal[i] = map.rotation * reference.face_normals[static_cast<std::size_t>(hits[i]->triangle)];
    c.distance[i] = map.scale * hits[i]->distance;
  }
  trim(c, trim_fraction);
  return c;
}

struct IcpResult {
  Similarity similarity;
  double rms = std::numeric_limits<double>::infinity();
  double forward_rms = std::numeric_limits<double>::infinity();  ///< reference -> target pairs only
  int iterations = 0;
};

/// Jacobian rows of one pair for the update (omega, sigma, tau): x' = x + omega x r + sigma r + tau,
/// r = x - c0. Point-to-plane: n . (x' - q); point-to-point: x' - q.
using Row7 = Eigen::Matrix<double, 1, 7>;
Row7 point_to_plane_row(const Vec3& r, const Vec3& n) {
  Row7 j;
  j.segment<3>(0) = r.cross(n).transpose();
  j(3) = n.dot(r);
  j.segment<3>(4) = n.transpose();
  return j;
}
Eigen::Matrix<double, 3, 7> point_to_point_rows(const Vec3& r) {
  Eigen::Matrix<double, 3, 7> j;
  Mat3 skew;
  skew << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  j.block<3, 3>(0, 0) = -skew;  // omega x r = -[r]x omega
  j.col(3) = r;
  j.block<3, 3>(0, 4) = Mat3::Identity();
  return j;
}

/// The two-way problem of one similarity: reference samples, target samples, both surfaces.
struct TwoWay {
  const TargetSurface& target;
  const TargetSurface& reference;
  const std::vector<Vec3>& reference_samples;
  const std::vector<Vec3>& target_samples;
};

/// Pairs both ways under `map`, and the combined trimmed RMS sqrt((f^2 + w r^2) / (1 + w)).
struct TwoWayPairs {
  Correspondences forward, reverse;
  double rms = std::numeric_limits<double>::infinity();
};

/// `previous`: the pairs under the previous map (or null), whose closest points bound the searches.
TwoWayPairs pairs_of(const TwoWay& problem, const Similarity& map, const SimilarityRegistrationOptions& options,
                     const TwoWayPairs* previous = nullptr) {
  TwoWayPairs p;
  std::vector<Vec3> x(problem.reference_samples.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = map.apply(problem.reference_samples[i]);
  p.forward = correspond(problem.target, x, options.trim_fraction, previous ? &previous->forward : nullptr);
  const double w = options.reverse_weight;
  double f2 = p.forward.kept_count > 0 ? p.forward.trimmed_rms * p.forward.trimmed_rms
                                       : std::numeric_limits<double>::infinity();
  if (w > 0.0) {
    p.reverse = correspond_reverse(problem.reference, map, problem.target_samples, options.reverse_trim_fraction,
                                   previous ? &previous->reverse : nullptr);
    const double r2 = p.reverse.trimmed_rms * p.reverse.trimmed_rms;
    p.rms = std::sqrt((f2 + w * r2) / (1.0 + w));
  } else {
    p.rms = std::sqrt(f2);
  }
  return p;
}

/// `plane`: when not null, the target's symmetry plane that the reference's stays on (only the turn about its
/// normal, the scale about a point on it and shifts within it are free). `settle`: stop at the noise floor
/// (options.stall_iterations) and keep the lowest-RMS iterate, for the final run; the brief runs that rank the
/// starts take their fixed iterations. `first`: when not null, the pairs of `problem` under `start` (found before),
/// used for the first iteration instead of searching them again. `last`: when not null, receives the pairs under
/// the returned similarity (left empty when that is an earlier iterate).
IcpResult scaled_icp(const TwoWay& problem, Similarity start, double size, const SimilarityRegistrationOptions& options,
                     int max_iterations, const Plane* plane = nullptr, bool settle = false,
                     const TwoWayPairs* first = nullptr, std::optional<TwoWayPairs>* last = nullptr) {
  Eigen::Matrix<double, 7, 4> basis = Eigen::Matrix<double, 7, 4>::Zero();
  if (plane) {
    const Vec3 n = plane->normal.normalized();
    const Vec3 u = n.unitOrthogonal();
    const Vec3 v = n.cross(u);
    basis.block<3, 1>(0, 0) = n;
    basis(3, 1) = 1.0;
    basis.block<3, 1>(4, 2) = u;
    basis.block<3, 1>(4, 3) = v;
  }
  IcpResult result;
  result.similarity = start;
  IcpResult best;  // the lowest trimmed RMS so far
  double stall_reference = std::numeric_limits<double>::infinity();
  int stalled = 0;
  const double w2 = options.point_weight * options.point_weight;
  TwoWayPairs p;
  for (int it = 0; it < max_iterations; ++it) {
    if (it == 0 && first) {
      p = *first;
    } else {
      p = pairs_of(problem, result.similarity, options, it > 0 ? &p : nullptr);
    }
    result.rms = p.rms;
    result.forward_rms = p.forward.kept_count > 0 ? p.forward.trimmed_rms : std::numeric_limits<double>::infinity();
    result.iterations = it;
    if (p.forward.kept_count == 0) break;  // the reference left the target's view
    if (settle && p.rms < best.rms) best = result;
    // At the noise floor of the trimmed pairs (the kept set flips) the RMS stops falling and the steps never
    // reach the tolerance: stop once it has not fallen by stall_tolerance for stall_iterations iterations.
    if (settle && options.stall_iterations > 0) {
      if (p.rms < stall_reference * (1.0 - options.stall_tolerance)) {
        stall_reference = p.rms;
        stalled = 0;
      } else if (++stalled >= options.stall_iterations) {
        break;
      }
    }
    Vec3 c0 = Vec3::Zero();
    for (std::size_t i = 0; i < p.forward.moving.size(); ++i) {
      if (p.forward.kept[i]) c0 += p.forward.moving[i];
    }
    c0 /= static_cast<double>(p.forward.kept_count);
    if (plane) c0 = plane->project(c0);
    Eigen::Matrix<double, 7, 7> h = Eigen::Matrix<double, 7, 7>::Zero();
    Eigen::Matrix<double, 7, 1> g = Eigen::Matrix<double, 7, 1>::Zero();
    // Each direction weighted by its share, so neither outvotes the other by its sample count.
    const auto accumulate = [&](const Correspondences& c, double weight) {
      if (c.kept_count == 0 || weight <= 0.0) return;
      const double share = weight / static_cast<double>(c.kept_count);
      for (std::size_t i = 0; i < c.moving.size(); ++i) {
        if (!c.kept[i]) continue;
        const Vec3 r = c.moving[i] - c0;
        const Vec3 e = c.moving[i] - c.fixed[i];
        const Row7 jp = point_to_plane_row(r, c.normal[i]);
        h += share * jp.transpose() * jp;
        g += share * jp.transpose() * c.normal[i].dot(e);
        const Eigen::Matrix<double, 3, 7> jq = point_to_point_rows(r);
        h += share * w2 * jq.transpose() * jq;
        g += share * w2 * jq.transpose() * e;
      }
    };
    accumulate(p.forward, 1.0);
    accumulate(p.reverse, options.reverse_weight);
    if (options.scale_prior_sd > 0.0) {
      // Gaussian prior on log scale about 0 (both skulls in mm), weighted by the current residual: the MAP step.
      const double lambda = p.rms * p.rms / (options.scale_prior_sd * options.scale_prior_sd);
      h(3, 3) += lambda;
      g(3) += lambda * std::log(result.similarity.scale);
    }
    for (int k = 0; k < 7; ++k) h(k, k) += 1e-9 * h.diagonal().maxCoeff() + 1e-12;
    Eigen::Matrix<double, 7, 1> delta;
    if (plane) {
      const Eigen::Matrix<double, 4, 4> hr = basis.transpose() * h * basis;
      const Eigen::Matrix<double, 4, 1> gr = basis.transpose() * g;
      delta = -basis * hr.ldlt().solve(gr);
    } else {
      delta = -h.ldlt().solve(g);
    }
    if (!delta.allFinite()) throw NumericError("similarity registration: singular Gauss-Newton system");
    const Vec3 omega = delta.segment<3>(0);
    const double sigma = delta(3);
    const Vec3 tau = delta.segment<3>(4);
    const double angle = omega.norm();
    const Mat3 r_inc = angle > 0.0 ? Mat3(Eigen::AngleAxisd(angle, omega / angle)) : Mat3::Identity();
    const double s_inc = std::exp(sigma);
    Similarity next;
    next.scale = s_inc * result.similarity.scale;
    next.rotation = r_inc * result.similarity.rotation;
    next.translation = s_inc * (r_inc * (result.similarity.translation - c0)) + c0 + tau;
    result.similarity = next;
    if (angle + std::abs(sigma) + tau.norm() / size < options.tolerance) break;
  }
  TwoWayPairs final_pairs = pairs_of(problem, result.similarity, options, max_iterations > 0 ? &p : nullptr);
  result.rms = final_pairs.rms;
  result.forward_rms =
      final_pairs.forward.kept_count > 0 ? final_pairs.forward.trimmed_rms : std::numeric_limits<double>::infinity();
  if (last) {
    if (best.rms < result.rms) {
      last->reset();
    } else {
      *last = std::move(final_pairs);
    }
  }
  if (best.rms < result.rms) {
    const int iterations = result.iterations;
    result = best;
    result.iterations = iterations;
  }
  return result;
}

/// The 24 proper rotations that map the coordinate axes onto signed coordinate axes.
std::vector<Mat3> axis_rotations() {
  std::vector<Mat3> out;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& perm : perms) {
    for (int signs = 0; signs < 8; ++signs) {
      Mat3 r = Mat3::Zero();
      for (int c = 0; c < 3; ++c) r(perm[c], c) = (signs >> c) & 1 ? -1.0 : 1.0;
      if (r.determinant() > 0.0) out.push_back(r);
    }
  }
  return out;
}

/// Target samples for the reverse pairs: every k-th vertex not on a cap, at most `max_samples`.
std::vector<Vec3> target_samples(const TriMesh& target, const TargetSurface& surface, std::size_t max_samples) {
  std::vector<char> on_cap(target.positions.size(), 0);
  for (std::size_t t = 0; t < target.triangles.size(); ++t) {
    if (!surface.cap[t]) continue;
    for (Index v : target.triangles[t]) on_cap[static_cast<std::size_t>(v)] = 1;
  }
  std::vector<Vec3> free;
  free.reserve(target.positions.size());
  for (std::size_t i = 0; i < target.positions.size(); ++i) {
    if (!on_cap[i]) free.push_back(target.positions[i]);
  }
  if (free.empty()) free = target.positions;
  const std::size_t stride = std::max<std::size_t>(1, (free.size() + max_samples - 1) / max_samples);
  std::vector<Vec3> samples;
  for (std::size_t i = 0; i < free.size(); i += stride) samples.push_back(free[i]);
  return samples;
}

SymmetryPlaneOptions symmetry_options() {
  SymmetryPlaneOptions o;
  o.max_iterations = 50;
  o.max_samples = 1500;
  return o;
}

/// Proper rotation taking unit vector a onto unit vector b.
Mat3 rotation_between(const Vec3& a, const Vec3& b) {
  return Eigen::Quaterniond::FromTwoVectors(a, b).toRotationMatrix();
}

}  // namespace

double rotation_angle_deg(const Mat3& a, const Mat3& b) {
  // Through the quaternion (2 atan2(|v|, |w|)): acos of the trace loses half the digits near 0.
  return Eigen::AngleAxisd(Mat3(a.transpose() * b)).angle() * 180.0 / M_PI;
}

std::vector<std::size_t> distinct_basins(const std::vector<Similarity>& ranked, double angle_deg,
                                         std::size_t max_count) {
  require_input(angle_deg >= 0.0, "similarity registration", "basin_angle_deg", "must not be negative");
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < ranked.size() && out.size() < max_count; ++i) {
    bool known = false;
    for (std::size_t j : out) known = known || rotation_angle_deg(ranked[j].rotation, ranked[i].rotation) <= angle_deg;
    if (!known) out.push_back(i);
  }
  return out;
}

namespace {

/// fit_target_symmetry on a prebuilt query of `target` (one BVH for all the fits).
SymmetryPlaneFit fit_target_symmetry(const TriMesh& target, const ClosestPointQuery& query) {
  check_mesh(target, "target skull");
  const Moments mt = moments(target.positions);
  const Eigen::SelfAdjointEigenSolver<Mat3> et(mt.covariance);
  const SymmetryPlaneOptions o = symmetry_options();
  SymmetryPlaneFit best;
  best.rms_mm = std::numeric_limits<double>::infinity();
  std::vector<Vec3> normals = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  for (int k = 0; k < 3; ++k) normals.push_back(et.eigenvectors().col(k));
  // The fits are independent: run side by side, the best taken in the normals' order (the earliest wins ties).
  std::vector<SymmetryPlaneFit> fits(normals.size());
  parallel_for(
      0, normals.size(),
      [&](std::size_t k) {
        fits[k] = fit_symmetry_plane(target, query, Plane{mt.centroid, normals[k]}, o);
      },
      1);
  for (const SymmetryPlaneFit& fit : fits) {
    if (fit.rms_mm < best.rms_mm) best = fit;
  }
  return best;
}

}  // namespace

SymmetryPlaneFit fit_target_symmetry(const TriMesh& target) {
  check_mesh(target, "target skull");
  return fit_target_symmetry(target, ClosestPointQuery(target));
}

namespace {

IcpResult similarity_stage(const TriMesh& reference, const TriMesh& target, const TargetSurface& surface,
                           const SimilarityRegistrationOptions& options, std::vector<Vec3>* samples_out,
                           std::optional<Plane>* target_plane_out = nullptr) {
  check_mesh(reference, "reference skull");
  check_mesh(target, "target skull");
  require_input(options.max_samples >= 16, "similarity registration", "max_samples", "must be at least 16");
  require_input(options.max_iterations >= 1, "similarity registration", "max_iterations", "must be at least 1");
  require_input(options.final_candidates >= 1, "similarity registration", "final_candidates", "must be at least 1");
  require_input(options.basin_samples >= 16, "similarity registration", "basin_samples", "must be at least 16");
  require_input(options.basin_iterations >= 1, "similarity registration", "basin_iterations", "must be at least 1");
  require_input(options.refine_iterations >= 1, "similarity registration", "refine_iterations", "must be at least 1");
  require_input(options.stall_iterations >= 0, "similarity registration", "stall_iterations", "must not be negative");
  require_input(options.stall_tolerance >= 0.0, "similarity registration", "stall_tolerance", "must not be negative");
  require_input(options.trim_fraction >= 0.0 && options.trim_fraction < 0.9, "similarity registration", "trim_fraction",
                "must lie in [0, 0.9)");
  require_input(options.reverse_trim_fraction >= 0.0 && options.reverse_trim_fraction < 0.9, "similarity registration",
                "reverse_trim_fraction", "must lie in [0, 0.9)");
  require_input(options.reverse_weight >= 0.0, "similarity registration", "reverse_weight", "must not be negative");
  require_input(options.point_weight >= 0.0, "similarity registration", "point_weight", "must not be negative");
  const Moments mr = moments(reference.positions);
  const Moments mt = moments(target.positions);
  require_input(mr.covariance.trace() > 0.0, "reference skull", "", "all vertices coincide");
  require_input(mt.covariance.trace() > 0.0, "target skull", "", "all vertices coincide");
  const double moment_scale = std::sqrt(mt.covariance.trace() / mr.covariance.trace());
  const double size = std::sqrt(mt.covariance.trace());
  // With the prior both skulls are in mm and the start is its centre, scale 1: a partial target biases the moments.
  const double start_scale = options.scale_prior_sd > 0.0 ? 1.0 : moment_scale;

  const TargetSurface reference_surface(reference, ScanFieldOfView{});
  std::optional<Plane> plane;
  Plane reference_plane;
  std::vector<Mat3> rotations;
  if (options.reference_midsagittal) {
    // The target's plane, and the reference's refined by the same fit so that both are the planes of best
    // symmetry: independent, so fitted side by side.
    parallel_invoke([&] { plane = fit_target_symmetry(target, surface.query).plane; },
                    [&] {
                      reference_plane = fit_symmetry_plane(reference, reference_surface.query,
                                                           *options.reference_midsagittal, symmetry_options())
                                            .plane;
                    });
    const Vec3 nr = reference_plane.normal;
    for (double sign : {1.0, -1.0}) {
      const Mat3 base = rotation_between(nr, sign * plane->normal);
      for (int k = 0; k < 12; ++k) {
        rotations.push_back(Eigen::AngleAxisd(k * M_PI / 6.0, plane->normal).toRotationMatrix() * base);
      }
    }
  } else {
    rotations.push_back(Mat3::Identity());
  }
  if (options.principal_axis_starts && !plane) {
    const Eigen::SelfAdjointEigenSolver<Mat3> er(mr.covariance);
    const Eigen::SelfAdjointEigenSolver<Mat3> et(mt.covariance);
    Mat3 ar = er.eigenvectors();
    Mat3 at = et.eigenvectors();
    if (ar.determinant() < 0.0) ar.col(0) *= -1.0;
    if (at.determinant() < 0.0) at.col(0) *= -1.0;
    for (const Vec3& signs : {Vec3(1, 1, 1), Vec3(-1, -1, 1), Vec3(-1, 1, -1), Vec3(1, -1, -1)}) {
      rotations.push_back(at * signs.asDiagonal() * ar.transpose());
    }
  }
  if (options.quarter_turn_starts && !plane) {
    for (const Mat3& r : axis_rotations()) {
      if (!r.isIdentity()) rotations.push_back(r);
    }
  }
  std::vector<Similarity> starts;
  for (const Mat3& r : rotations) {
    Similarity s;
    s.scale = start_scale;
    s.rotation = r;
    s.translation = mt.centroid - start_scale * (r * mr.centroid);
    if (plane) {
      // The reference's plane onto the target's.
      s.translation -= plane->signed_distance(s.apply(reference_plane.point)) * plane->normal;
    }
    starts.push_back(s);
  }
  const std::vector<Vec3> samples = sample_vertices(reference, options.max_samples);
  const std::vector<Vec3> targets = target_samples(target, surface, options.max_samples / 2);
  // Every start briefly on few samples, the best few further, then the best on all samples.
  const std::vector<Vec3> coarse = sample_vertices(reference, std::min<std::size_t>(options.max_samples, 250));
  const std::vector<Vec3> coarse_targets =
      target_samples(target, surface, std::min<std::size_t>(options.max_samples, 250));
  const TwoWay coarse_problem{surface, reference_surface, coarse, coarse_targets};
  // The runs from each start (and below, from each candidate and basin) are independent: run side by side, each
  // kept in its start's place, so the ranking does not depend on the thread count.
  const Plane* const on_plane = plane ? &*plane : nullptr;
  // Each run's last pairs start its refined run below (the same problem and map: the same pairs).
  std::vector<IcpResult> runs(starts.size());
  std::vector<std::optional<TwoWayPairs>> run_pairs(starts.size());
  parallel_for(
      0, starts.size(),
      [&](std::size_t k) {
        runs[k] = scaled_icp(coarse_problem, starts[k], size, options, std::min(options.max_iterations, 10), on_plane,
                             false, nullptr, &run_pairs[k]);
      },
      1);
  std::vector<std::size_t> order(runs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return runs[a].rms < runs[b].rms; });
  // The best (refined_starts, all by default) further on few samples, then ranked by their RMS: after the brief
  // runs a start may still lie between basins, and the best basin is not always among the few best brief runs.
  const std::size_t further = std::min<std::size_t>(
      std::max<std::size_t>({3, options.final_candidates, options.basin_candidates, options.refined_starts}),
      order.size());
  std::vector<IcpResult> candidates(further);
  parallel_for(
      0, further,
      [&](std::size_t k) {
        const std::optional<TwoWayPairs>& known = run_pairs[order[k]];
        candidates[k] = scaled_icp(coarse_problem, runs[order[k]].similarity, size, options,
                                   std::min(options.max_iterations, options.refine_iterations), on_plane, false,
                                   known ? &*known : nullptr);
      },
      1);
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const IcpResult& a, const IcpResult& b) { return a.rms < b.rms; });
  // One candidate per basin (the lowest two-way RMS of each), at most basin_candidates: on few samples the two-way
  // RMS of two basins (a skull pitched about the plane's normal, say) can differ by a few per cent either way.
  std::vector<Similarity> ranked;
  for (const IcpResult& c : candidates) ranked.push_back(c.similarity);
  const std::vector<std::size_t> basins = distinct_basins(ranked, options.basin_angle_deg, options.basin_candidates);
  if (basins.size() > 1) {
    // Each basin's candidate on more samples; ranked by the reference -> target pairs (the skull-to-target fit the
    // landmarks are carried by), which tell the basins apart where the two-way RMS does not (the reverse pairs
    // also count parts the reference lacks: vertebrae, the CT table).
    const std::vector<Vec3> medium = sample_vertices(reference, std::min(options.max_samples, options.basin_samples));
    const std::vector<Vec3> medium_targets =
        target_samples(target, surface, std::min(options.max_samples, options.basin_samples) / 2);
    const TwoWay medium_problem{surface, reference_surface, medium, medium_targets};
    std::vector<IcpResult> settled(basins.size());
    parallel_for(
        0, basins.size(),
        [&](std::size_t k) {
          settled[k] = scaled_icp(medium_problem, candidates[basins[k]].similarity, size, options,
                                  std::min(options.max_iterations, options.basin_iterations), on_plane);
        },
        1);
    std::vector<double> forward(settled.size());
    for (std::size_t k = 0; k < settled.size(); ++k) forward[k] = settled[k].forward_rms;
    std::vector<std::size_t> by_forward(settled.size());
    for (std::size_t k = 0; k < by_forward.size(); ++k) by_forward[k] = k;
    std::stable_sort(by_forward.begin(), by_forward.end(),
                     [&](std::size_t a, std::size_t b) { return forward[a] < forward[b]; });
    std::vector<IcpResult> reordered;
    for (std::size_t k : by_forward) reordered.push_back(settled[k]);
    // The other candidates after the basins' (they may still run on all samples with final_candidates > 1).
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      if (std::find(basins.begin(), basins.end(), k) == basins.end()) reordered.push_back(candidates[k]);
    }
    candidates = std::move(reordered);
  }
  candidates.resize(std::min(candidates.size(), options.final_candidates));
  const std::size_t lowest = 0;
  const TwoWay problem{surface, reference_surface, samples, targets};
  if (plane) {
    // The target's plane refitted from the registered reference's (the first fit started from the axes), and
    // every candidate turned and shifted onto it.
    const Similarity& b = candidates[lowest].similarity;
    plane = fit_symmetry_plane(target, surface.query,
                               Plane{b.apply(reference_plane.point), b.rotation * reference_plane.normal},
                               symmetry_options())
                .plane;
    for (IcpResult& c : candidates) {
      const Similarity a = c.similarity;
      const Vec3 mapped_normal = a.rotation * reference_plane.normal;
      const Vec3 on = a.apply(reference_plane.point);
      const Mat3 turn = rotation_between(mapped_normal, plane->normal);
      c.similarity.rotation = turn * a.rotation;
      c.similarity.translation = turn * (a.translation - on) + on;
      c.similarity.translation -= plane->signed_distance(c.similarity.apply(reference_plane.point)) * plane->normal;
    }
  }
  // Each candidate on all samples; kept: the lowest RMS of the reference -> target pairs (the fit the landmarks
  // are carried by).
  IcpResult fine;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const IcpResult r = scaled_icp(problem, candidates[k].similarity, size, options, options.max_iterations,
                                   plane ? &*plane : nullptr, true);
    if (k == 0 || r.forward_rms < fine.forward_rms) fine = r;  // strict: the earliest wins ties
  }

  if (samples_out) *samples_out = samples;
  if (target_plane_out) *target_plane_out = plane;
  return fine;
}

/// Columns of the non-rigid stage's normal matrix computed per task.
constexpr std::size_t kNodeBlock = 24;

double gaussian(double squared_distance, double sigma) {
  return std::exp(-squared_distance / (2.0 * sigma * sigma));
}

}  // namespace

Vec3 SkullRegistration::displacement(const Vec3& y) const {
  Vec3 u = Vec3::Zero();
  for (std::size_t j = 0; j < node_positions.size(); ++j) {
    u += node_weights[j] * gaussian((y - node_positions[j]).squaredNorm(), kernel_width_mm);
  }
  return u;
}

Vec3 SkullRegistration::map(const Vec3& reference_point) const {
  const Vec3 y = similarity.apply(reference_point);
  return y + displacement(y);
}

double SkullRegistration::local_residual_mm(const Vec3& target_point, double radius_mm) const {
  double sum = 0.0;
  std::size_t count = 0;
  const double r2 = radius_mm * radius_mm;
  for (std::size_t i = 0; i < sample_positions.size(); ++i) {
    const bool in_view = i >= sample_in_view.size() || sample_in_view[i];
    if (in_view && (sample_positions[i] - target_point).squaredNorm() <= r2) {
      sum += sample_residual_mm[i] * sample_residual_mm[i];
      ++count;
    }
  }
  return count == 0 ? rms_mm : std::sqrt(sum / static_cast<double>(count));
}

Similarity register_similarity(const TriMesh& reference, const TriMesh& target,
                               const SimilarityRegistrationOptions& options, double* rms_mm, int* iterations) {
  check_mesh(target, "target skull");
  const TargetSurface surface(target, options.target_view);
  const IcpResult r = similarity_stage(reference, target, surface, options, nullptr);
  if (rms_mm) *rms_mm = r.rms;
  if (iterations) *iterations = r.iterations;
  return r.similarity;
}

SkullRegistration register_skull(const TriMesh& reference, const TriMesh& target,
                                 const SkullRegistrationOptions& options) {
  const NonRigidRegistrationOptions& nr = options.non_rigid;
  const std::string where = "non-rigid registration";
  require_input(nr.node_count >= 4, where, "node_count", "must be at least 4");
  require_input(nr.kernel_width > 0.0, where, "kernel_width", "must be positive");
  require_input(!nr.stiffness_schedule.empty(), where, "stiffness_schedule", "must not be empty");
  for (double l : nr.stiffness_schedule) require_input(l > 0.0, where, "stiffness_schedule", "values must be positive");
  require_input(nr.iterations_per_stage >= 1, where, "iterations_per_stage", "must be at least 1");
  require_input(nr.trim_fraction >= 0.0 && nr.trim_fraction < 0.9, where, "trim_fraction", "must lie in [0, 0.9)");
  require_input(nr.tangential_weight >= 0.0 && nr.tangential_weight <= 1.0, where, "tangential_weight",
                "must lie in [0, 1]");
  require_input(nr.reverse_weight >= 0.0, where, "reverse_weight", "must not be negative");
  require_input(nr.reverse_trim_fraction >= 0.0 && nr.reverse_trim_fraction < 0.9, where, "reverse_trim_fraction",
                "must lie in [0, 0.9)");
  require_input(nr.reverse_normal_cos >= -1.0 && nr.reverse_normal_cos <= 1.0, where, "reverse_normal_cos",
                "must lie in [-1, 1]");
  check_mesh(target, "target skull");
  const TargetSurface surface(target, options.similarity.target_view);
  std::vector<Vec3> samples;
  std::optional<Plane> target_plane;
  const IcpResult sim = similarity_stage(reference, target, surface, options.similarity, &samples, &target_plane);

  SkullRegistration reg;
  reg.similarity = sim.similarity;
  reg.target_midsagittal = target_plane;
  reg.similarity_iterations = sim.iterations;
  const std::size_t s_count = samples.size();
  std::vector<Vec3> y(s_count);
  for (std::size_t i = 0; i < s_count; ++i) y[i] = sim.similarity.apply(samples[i]);
  // Reference -> target, as the non-rigid stage measures it.
  const Correspondences similarity_pairs =
      correspond(surface, y, options.non_rigid_enabled ? nr.trim_fraction : options.similarity.trim_fraction);
  reg.similarity_rms_mm = similarity_pairs.trimmed_rms;
  reg.rms_mm = reg.similarity_rms_mm;

  if (options.non_rigid_enabled) {
    // Nodes: farthest-point samples, from the sample nearest the centroid (deterministic).
    const std::size_t n_nodes = std::min(nr.node_count, s_count);
    const Moments m = moments(y);
    std::size_t first = 0;
    for (std::size_t i = 1; i < s_count; ++i) {
      if ((y[i] - m.centroid).squaredNorm() < (y[first] - m.centroid).squaredNorm()) first = i;
    }
    std::vector<double> d2(s_count, std::numeric_limits<double>::infinity());
    std::size_t next = first;
    for (std::size_t k = 0; k < n_nodes; ++k) {
      reg.node_positions.push_back(y[next]);
      std::size_t far = 0;
      for (std::size_t i = 0; i < s_count; ++i) {
        d2[i] = std::min(d2[i], (y[i] - y[next]).squaredNorm());
        if (d2[i] > d2[far]) far = i;
      }
      next = far;
    }
    double spacing = 0.0;
    for (std::size_t j = 0; j < n_nodes; ++j) {
      double nearest = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < n_nodes; ++k) {
        if (k != j) nearest = std::min(nearest, (reg.node_positions[j] - reg.node_positions[k]).squaredNorm());
      }
      spacing += std::sqrt(nearest);
    }
    spacing /= static_cast<double>(n_nodes);
    const double sigma = nr.kernel_width * spacing;
    reg.kernel_width_mm = sigma;

    Eigen::MatrixXd a(static_cast<Eigen::Index>(s_count), static_cast<Eigen::Index>(n_nodes));
    parallel_for(0, s_count, [&](std::size_t i) {
      for (std::size_t j = 0; j < n_nodes; ++j) {
        a(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
            gaussian((y[i] - reg.node_positions[j]).squaredNorm(), sigma);
      }
    });
    Eigen::MatrixXd k(static_cast<Eigen::Index>(n_nodes), static_cast<Eigen::Index>(n_nodes));
    for (std::size_t i = 0; i < n_nodes; ++i) {
      for (std::size_t j = 0; j < n_nodes; ++j) {
        k(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
            gaussian((reg.node_positions[i] - reg.node_positions[j]).squaredNorm(), sigma);
      }
    }
    // Reverse pairs: target samples to their nearest moving reference sample (the target's own shape pulls the
    // reference where the reference's closest points slide past it, a longer chin or jaw for one), point to the
    // target's tangent plane there; the worst reverse_trim_fraction dropped (parts the reference lacks).
    const std::vector<Vec3> targets = nr.reverse_weight > 0.0
                                          ? target_samples(target, surface, options.similarity.max_samples / 2)
                                          : std::vector<Vec3>{};
    const std::size_t t_count = targets.size();
    std::vector<Vec3> target_normal(t_count);
    {
      const auto hits = surface.query.query_batch(targets);
      for (std::size_t t = 0; t < t_count; ++t) {
        target_normal[t] = surface.face_normals[static_cast<std::size_t>(hits[t]->triangle)];
      }
    }
    // The reference samples' normals (the samples are every k-th vertex, as sample_vertices takes them), turned by
    // the similarity: a reverse pair joins surfaces that face the same way (not a vertebra to the jaw's underside).
    std::vector<Vec3> sample_normal;
    if (t_count > 0) {
      sample_normal = every_kth(vertex_normals(reference), options.similarity.max_samples);
      for (Vec3& n : sample_normal) n = sim.similarity.rotation * n;
      if (sample_normal.size() != s_count) throw NumericError("non-rigid registration: sample normals do not match");
    }
    const double reverse_scale = std::sqrt(nr.reverse_weight);
    const auto rows = static_cast<Eigen::Index>(s_count + t_count);
    Eigen::MatrixXd w = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n_nodes), 3);
    std::vector<Vec3> x = y;
    Correspondences c = similarity_pairs;
    double rms = reg.similarity_rms_mm;
    // The desired displacement of a moving sample from its pair: the normal part of the offset in full, the
    // tangential part weighted (lets it slide).
    const auto wanted = [&](std::size_t i, const Vec3& offset, const Vec3& n) -> Vec3 {
      const Vec3 normal_part = n * n.dot(offset);
      return (x[i] - y[i]) + normal_part + nr.tangential_weight * (offset - normal_part);
    };
    for (double stiffness : nr.stiffness_schedule) {
      for (int it = 0; it < nr.iterations_per_stage; ++it) {
        c = correspond(surface, x, nr.trim_fraction, &c);
        rms = c.trimmed_rms;
        Eigen::MatrixXd am(rows, static_cast<Eigen::Index>(n_nodes));
        Eigen::MatrixXd d(rows, 3);
        for (std::size_t i = 0; i < s_count; ++i) {
          const auto row = static_cast<Eigen::Index>(i);
          if (c.kept[i]) {
            am.row(row) = a.row(row);
            d.row(row) = wanted(i, c.fixed[i] - x[i], c.normal[i]).transpose();
          } else {
            am.row(row).setZero();
            d.row(row).setZero();
          }
        }
        if (t_count > 0) {
          const NearestPointIndex moving(x);
          const std::vector<NearestPoint> near = moving.nearest_batch(targets);
          Correspondences r;
          r.distance.resize(t_count);
          r.valid.assign(t_count, 1);
          for (std::size_t t = 0; t < t_count; ++t) {
            r.distance[t] = near[t].distance;
            r.valid[t] = static_cast<char>(sample_normal[near[t].index].dot(target_normal[t]) > nr.reverse_normal_cos);
          }
          trim(r, nr.reverse_trim_fraction);
          for (std::size_t t = 0; t < t_count; ++t) {
            const auto row = static_cast<Eigen::Index>(s_count + t);
            const std::size_t i = near[t].index;
            if (r.kept[t]) {
              am.row(row) = reverse_scale * a.row(static_cast<Eigen::Index>(i));
              d.row(row) = reverse_scale * wanted(i, targets[t] - x[i], target_normal[t]).transpose();
            } else {
              am.row(row).setZero();
              d.row(row).setZero();
            }
          }
        }
        // A^T A in column blocks side by side (a fixed split, whatever the thread count): the one dense product
        // of the stage, which would otherwise hold one core while the other waits.
        Eigen::MatrixXd h(static_cast<Eigen::Index>(n_nodes), static_cast<Eigen::Index>(n_nodes));
        const std::size_t column_blocks = (n_nodes + kNodeBlock - 1) / kNodeBlock;
        parallel_for(
            0, column_blocks,
            [&](std::size_t b) {
              const auto j0 = static_cast<Eigen::Index>(b * kNodeBlock);
              const auto nb = static_cast<Eigen::Index>(std::min(kNodeBlock, n_nodes - b * kNodeBlock));
              h.middleCols(j0, nb).noalias() = am.transpose() * am.middleCols(j0, nb);
            },
            1);
        const double lambda = stiffness * h.trace() / k.trace();
        h += lambda * k;
        h.diagonal().array() += 1e-12 * h.trace() / static_cast<double>(n_nodes);
        w = h.ldlt().solve(am.transpose() * d);
        if (!w.allFinite()) throw NumericError("non-rigid registration: singular regularised system");
        const Eigen::MatrixXd u = a * w;
        for (std::size_t i = 0; i < s_count; ++i) x[i] = y[i] + u.row(static_cast<Eigen::Index>(i)).transpose();
      }
    }
    reg.node_weights.resize(n_nodes);
    for (std::size_t j = 0; j < n_nodes; ++j) reg.node_weights[j] = w.row(static_cast<Eigen::Index>(j)).transpose();
    c = correspond(surface, x, nr.trim_fraction, &c);
    rms = c.trimmed_rms;
    reg.rms_mm = rms;
    reg.sample_positions = x;
    reg.sample_residual_mm = c.distance;
    reg.sample_in_view = c.valid;
  } else {
    const Correspondences& c = similarity_pairs;
    reg.sample_positions = y;
    reg.sample_residual_mm = c.distance;
    reg.sample_in_view = c.valid;
  }
  return reg;
}

}  // namespace forensim
