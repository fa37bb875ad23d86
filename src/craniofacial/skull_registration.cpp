#include "craniofacial/skull_registration.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "spatial/closest_point.hpp"

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

/// Every k-th vertex, at most `max_samples`.
std::vector<Vec3> sample_vertices(const TriMesh& mesh, std::size_t max_samples) {
  const std::size_t n = mesh.positions.size();
  const std::size_t stride = std::max<std::size_t>(1, (n + max_samples - 1) / std::max<std::size_t>(1, max_samples));
  std::vector<Vec3> samples;
  samples.reserve(n / stride + 1);
  for (std::size_t i = 0; i < n; i += stride) samples.push_back(mesh.positions[i]);
  return samples;
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

/// Target surface with face normals for point-to-plane terms.
struct TargetSurface {
  explicit TargetSurface(const TriMesh& mesh) : query(mesh), face_normals(mesh.triangles.size()) {
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
      const Tri& t = mesh.triangles[f];
      const Vec3 n = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
      const double len = n.norm();
      face_normals[f] = len > 0.0 ? Vec3(n / len) : Vec3::Zero();
    }
  }
  ClosestPointQuery query;
  std::vector<Vec3> face_normals;
};

struct Correspondences {
  std::vector<Vec3> closest;
  std::vector<Vec3> normal;
  std::vector<double> distance;
  std::vector<char> kept;
  double trimmed_rms = 0.0;
};

/// Closest points of `points`, with the worst `trim_fraction` marked as dropped.
Correspondences correspond(const TargetSurface& target, const std::vector<Vec3>& points, double trim_fraction) {
  Correspondences c;
  const auto hits = target.query.query_batch(points);
  const std::size_t n = points.size();
  c.closest.resize(n);
  c.normal.resize(n);
  c.distance.resize(n);
  c.kept.assign(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    c.closest[i] = hits[i]->point;
    c.normal[i] = target.face_normals[static_cast<std::size_t>(hits[i]->triangle)];
    c.distance[i] = hits[i]->distance;
  }
  const std::size_t keep = std::max<std::size_t>(
      1, n - std::min(n - 1, static_cast<std::size_t>(std::floor(trim_fraction * static_cast<double>(n)))));
  std::vector<double> sorted = c.distance;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(keep - 1), sorted.end());
  const double threshold = sorted[keep - 1];
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n && count < keep; ++i) {
    if (c.distance[i] <= threshold) {
      sum += c.distance[i] * c.distance[i];
      ++count;
    }
  }
  for (std::size_t i = 0, kept = 0; i < n; ++i) {
    c.kept[i] = (c.distance[i] <= threshold && kept < keep) ? 1 : 0;
    kept += static_cast<std::size_t>(c.kept[i]);
  }
  c.trimmed_rms = std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, count)));
  return c;
}

struct IcpResult {
  Similarity similarity;
  double rms = std::numeric_limits<double>::infinity();
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

IcpResult scaled_icp(const TargetSurface& target, const std::vector<Vec3>& samples, Similarity start, double size,
                     const SimilarityRegistrationOptions& options, int max_iterations) {
  IcpResult result;
  result.similarity = start;
  std::vector<Vec3> x(samples.size());
  for (int it = 0; it < max_iterations; ++it) {
    for (std::size_t i = 0; i < samples.size(); ++i) x[i] = result.similarity.apply(samples[i]);
    const Correspondences c = correspond(target, x, options.trim_fraction);
    result.rms = c.trimmed_rms;
    result.iterations = it;
    Vec3 c0 = Vec3::Zero();
    std::size_t kept = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (c.kept[i]) {
        c0 += x[i];
        ++kept;
      }
    }
    c0 /= static_cast<double>(kept);
    Eigen::Matrix<double, 7, 7> h = Eigen::Matrix<double, 7, 7>::Zero();
    Eigen::Matrix<double, 7, 1> g = Eigen::Matrix<double, 7, 1>::Zero();
    const double w2 = options.point_weight * options.point_weight;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (!c.kept[i]) continue;
      const Vec3 r = x[i] - c0;
      const Vec3 e = x[i] - c.closest[i];
      const Row7 jp = point_to_plane_row(r, c.normal[i]);
      h += jp.transpose() * jp;
      g += jp.transpose() * c.normal[i].dot(e);
      const Eigen::Matrix<double, 3, 7> jq = point_to_point_rows(r);
      h += w2 * jq.transpose() * jq;
      g += w2 * jq.transpose() * e;
    }
    for (int k = 0; k < 7; ++k) h(k, k) += 1e-9 * h.diagonal().maxCoeff() + 1e-12;
    const Eigen::Matrix<double, 7, 1> delta = -h.ldlt().solve(g);
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
  for (std::size_t i = 0; i < samples.size(); ++i) x[i] = result.similarity.apply(samples[i]);
  result.rms = correspond(target, x, options.trim_fraction).trimmed_rms;
  return result;
}

IcpResult similarity_stage(const TriMesh& reference, const TriMesh& target, const TargetSurface& surface,
                           const SimilarityRegistrationOptions& options, std::vector<Vec3>* samples_out) {
  check_mesh(reference, "reference skull");
  check_mesh(target, "target skull");
  require_input(options.max_samples >= 16, "similarity registration", "max_samples", "must be at least 16");
  require_input(options.max_iterations >= 1, "similarity registration", "max_iterations", "must be at least 1");
  require_input(options.trim_fraction >= 0.0 && options.trim_fraction < 0.9, "similarity registration", "trim_fraction",
                "must lie in [0, 0.9)");
  require_input(options.point_weight >= 0.0, "similarity registration", "point_weight", "must not be negative");
  const Moments mr = moments(reference.positions);
  const Moments mt = moments(target.positions);
  require_input(mr.covariance.trace() > 0.0, "reference skull", "", "all vertices coincide");
  require_input(mt.covariance.trace() > 0.0, "target skull", "", "all vertices coincide");
  const double scale = std::sqrt(mt.covariance.trace() / mr.covariance.trace());
  const double size = std::sqrt(mt.covariance.trace());

  std::vector<Similarity> starts;
  Similarity identity;
  identity.scale = scale;
  identity.translation = mt.centroid - scale * mr.centroid;
  starts.push_back(identity);
  if (options.principal_axis_starts) {
    const Eigen::SelfAdjointEigenSolver<Mat3> er(mr.covariance);
    const Eigen::SelfAdjointEigenSolver<Mat3> et(mt.covariance);
    Mat3 ar = er.eigenvectors();
    Mat3 at = et.eigenvectors();
    if (ar.determinant() < 0.0) ar.col(0) *= -1.0;
    if (at.determinant() < 0.0) at.col(0) *= -1.0;
    for (const Vec3& signs : {Vec3(1, 1, 1), Vec3(-1, -1, 1), Vec3(-1, 1, -1), Vec3(1, -1, -1)}) {
      Similarity s;
      s.scale = scale;
      s.rotation = at * signs.asDiagonal() * ar.transpose();
      s.translation = mt.centroid - scale * (s.rotation * mr.centroid);
      starts.push_back(s);
    }
  }
  // Coarse runs from every start on a few samples, then the best refined on all of them.
  const std::vector<Vec3> samples = sample_vertices(reference, options.max_samples);
  const std::vector<Vec3> coarse = sample_vertices(reference, std::min<std::size_t>(options.max_samples, 500));
  IcpResult best;
  for (const Similarity& start : starts) {
    const IcpResult r = scaled_icp(surface, coarse, start, size, options, std::min(options.max_iterations, 25));
    if (r.rms < best.rms) best = r;  // strict: the earliest start wins ties
  }
  IcpResult fine = scaled_icp(surface, samples, best.similarity, size, options, options.max_iterations);
  if (samples_out) *samples_out = samples;
  return fine;
}

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
    if ((sample_positions[i] - target_point).squaredNorm() <= r2) {
      sum += sample_residual_mm[i] * sample_residual_mm[i];
      ++count;
    }
  }
  return count == 0 ? rms_mm : std::sqrt(sum / static_cast<double>(count));
}

Similarity register_similarity(const TriMesh& reference, const TriMesh& target,
                               const SimilarityRegistrationOptions& options, double* rms_mm, int* iterations) {
  check_mesh(target, "target skull");
  const TargetSurface surface(target);
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
  check_mesh(target, "target skull");
  const TargetSurface surface(target);
  std::vector<Vec3> samples;
  const IcpResult sim = similarity_stage(reference, target, surface, options.similarity, &samples);

  SkullRegistration reg;
  reg.similarity = sim.similarity;
  reg.similarity_rms_mm = sim.rms;
  reg.rms_mm = sim.rms;
  reg.similarity_iterations = sim.iterations;
  const std::size_t s_count = samples.size();
  std::vector<Vec3> y(s_count);
  for (std::size_t i = 0; i < s_count; ++i) y[i] = sim.similarity.apply(samples[i]);

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
    Eigen::MatrixXd w = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n_nodes), 3);
    std::vector<Vec3> x = y;
    double rms = sim.rms;
    for (double stiffness : nr.stiffness_schedule) {
      for (int it = 0; it < nr.iterations_per_stage; ++it) {
        const Correspondences c = correspond(surface, x, nr.trim_fraction);
        rms = c.trimmed_rms;
        Eigen::MatrixXd am = a;
        Eigen::MatrixXd d(static_cast<Eigen::Index>(s_count), 3);
        for (std::size_t i = 0; i < s_count; ++i) {
          const auto row = static_cast<Eigen::Index>(i);
          const Vec3 offset = c.closest[i] - x[i];
          const Vec3& n = c.normal[i];
          const Vec3 normal_part = n * n.dot(offset);
          const Vec3 target_u = (x[i] - y[i]) + normal_part + nr.tangential_weight * (offset - normal_part);
          d.row(row) = target_u.transpose();
          if (!c.kept[i]) am.row(row).setZero();
        }
        Eigen::MatrixXd h = am.transpose() * am;
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
    const Correspondences c = correspond(surface, x, nr.trim_fraction);
    rms = c.trimmed_rms;
    reg.rms_mm = rms;
    reg.sample_positions = x;
    reg.sample_residual_mm = c.distance;
  } else {
    const Correspondences c = correspond(surface, y, options.similarity.trim_fraction);
    reg.sample_positions = y;
    reg.sample_residual_mm = c.distance;
  }
  return reg;
}

}  // namespace forensim
