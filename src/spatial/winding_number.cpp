#include "spatial/winding_number.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {
namespace {

constexpr int leaf_size = 8;
/// Subtrees with more triangles than this are built in parallel with their sibling.
constexpr int parallel_build_size = 4096;

/// Nodes of the tree over `count` triangles (the split below: halves, leaves of at most leaf_size).
int subtree_nodes(int count) {
  return count <= leaf_size ? 1 : 1 + subtree_nodes(count / 2) + subtree_nodes(count - count / 2);
}
constexpr double inv_4pi = 1.0 / (4.0 * std::numbers::pi);

}  // namespace

double triangle_solid_angle(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ra = a - q;
  const Vec3 rb = b - q;
  const Vec3 rc = c - q;
  const double la = ra.norm();
  const double lb = rb.norm();
  const double lc = rc.norm();
  const double numerator = ra.dot(rb.cross(rc));
  const double denominator = la * lb * lc + ra.dot(rb) * lc + ra.dot(rc) * lb + rb.dot(rc) * la;
  if (numerator == 0.0 && denominator == 0.0) return 0.0;  // q on the triangle's plane, at a corner or edge
  return 2.0 * std::atan2(numerator, denominator);
}

double winding_number_exact(const TriMesh& mesh, const Vec3& q) {
  double sum = 0.0;
  for (const Tri& t : mesh.triangles) {
    sum += triangle_solid_angle(q, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]);
  }
  return sum * inv_4pi;
}

WindingNumber::WindingNumber(const TriMesh& mesh, double beta) : m_beta(beta) {
  mesh.validate("winding number mesh");
  require_input(beta > 1.0 && std::isfinite(beta), "winding number", "beta",
                "accuracy parameter beta must be > 1, got " + std::to_string(beta));
  const std::size_t n = mesh.triangles.size();
  m_a.resize(n);
  m_b.resize(n);
  m_c.resize(n);
  std::vector<Vec3> centroids(n);
  for (std::size_t t = 0; t < n; ++t) {
    const Tri& tri = mesh.triangles[t];
    m_a[t] = mesh.positions[tri[0]];
    m_b[t] = mesh.positions[tri[1]];
    m_c[t] = mesh.positions[tri[2]];
    centroids[t] = (m_a[t] + m_b[t] + m_c[t]) / 3.0;
  }
  if (n > 0) {
    // Node indices are the preorder of the split, known from the subtree sizes: the two halves of a node are
    // built concurrently into their own ranges, the same tree at any thread count.
    m_nodes.resize(static_cast<std::size_t>(subtree_nodes(static_cast<int>(n))));
    build(0, 0, static_cast<int>(n), centroids);
  }
}

void WindingNumber::build(int index, int begin, int end, std::vector<Vec3>& centroids) {
  {
    Node& node = m_nodes[static_cast<std::size_t>(index)];
    node.box_min = Vec3::Constant(std::numeric_limits<double>::infinity());
    node.box_max = -node.box_min;
    double area_sum = 0.0;
    Vec3 weighted = Vec3::Zero();
    Vec3 plain = Vec3::Zero();
    for (int t = begin; t < end; ++t) {
      node.box_min = node.box_min.cwiseMin(centroids[t]);
      node.box_max = node.box_max.cwiseMax(centroids[t]);
      const double area = 0.5 * (m_b[t] - m_a[t]).cross(m_c[t] - m_a[t]).norm();
      area_sum += area;
      weighted += area * centroids[t];
      plain += centroids[t];
    }
    node.center = area_sum > 0.0 ? Vec3(weighted / area_sum) : Vec3(plain / (end - begin));
    for (int k = 0; k < 3; ++k) node.order2[k].setZero();
    for (int t = begin; t < end; ++t) {
      const Vec3 area_vector = 0.5 * (m_b[t] - m_a[t]).cross(m_c[t] - m_a[t]);
      const Vec3 d = centroids[t] - node.center;
      node.order0 += area_vector;
      node.order1 += area_vector * d.transpose();
      // Second moment of the triangle about the node centre: d d^T plus its own covariance (1/12 sum of
      // (v - c)(v - c)^T over its corners, exact for a uniform triangle).
      const Vec3 da = m_a[t] - centroids[t];
      const Vec3 db = m_b[t] - centroids[t];
      const Vec3 dc = m_c[t] - centroids[t];
      const Mat3 second = d * d.transpose() + (da * da.transpose() + db * db.transpose() + dc * dc.transpose()) / 12.0;
      for (int k = 0; k < 3; ++k) node.order2[k] += area_vector[k] * second;
      node.radius = std::max(
          {node.radius, (m_a[t] - node.center).norm(), (m_b[t] - node.center).norm(), (m_c[t] - node.center).norm()});
    }
  }
  if (end - begin <= leaf_size) {
    m_nodes[static_cast<std::size_t>(index)].first = begin;
    m_nodes[static_cast<std::size_t>(index)].count = end - begin;
    return;
  }
  // Median split of the centroids along the longest axis of their bounds.
  const Vec3 extent =
      m_nodes[static_cast<std::size_t>(index)].box_max - m_nodes[static_cast<std::size_t>(index)].box_min;
  int axis = 0;
  if (extent[1] > extent[axis]) axis = 1;
  if (extent[2] > extent[axis]) axis = 2;
  const int middle = begin + (end - begin) / 2;
  std::vector<int> order(static_cast<std::size_t>(end - begin));
  std::iota(order.begin(), order.end(), begin);
  std::nth_element(order.begin(), order.begin() + (middle - begin), order.end(),
                   [&](int x, int y) { return centroids[x][axis] < centroids[y][axis]; });
  {
    std::vector<Vec3> a(order.size()), b(order.size()), c(order.size()), centre(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
      a[i] = m_a[order[i]];
      b[i] = m_b[order[i]];
      c[i] = m_c[order[i]];
      centre[i] = centroids[order[i]];
    }
    std::copy(a.begin(), a.end(), m_a.begin() + begin);
    std::copy(b.begin(), b.end(), m_b.begin() + begin);
    std::copy(c.begin(), c.end(), m_c.begin() + begin);
    std::copy(centre.begin(), centre.end(), centroids.begin() + begin);
  }
  const int left = index + 1;
  const int right = left + subtree_nodes(middle - begin);
  if (end - begin > parallel_build_size) {
    parallel_invoke([&] { build(left, begin, middle, centroids); }, [&] { build(right, middle, end, centroids); });
  } else {
    build(left, begin, middle, centroids);
    build(right, middle, end, centroids);
  }
  Node& node = m_nodes[static_cast<std::size_t>(index)];
  node.first = left;
  node.count = 0;
  node.right = right;
}

double WindingNumber::evaluate_node(int root, const Vec3& q) const {
  double sum = 0.0;  // in units of 4 pi steradians
  int stack[128];
  int top = 0;
  stack[top++] = root;
  while (top > 0) {
    const Node& node = m_nodes[stack[--top]];
    const Vec3 r = node.center - q;
    const double dist2 = r.squaredNorm();
    if (dist2 > m_beta * m_beta * node.radius * node.radius) {
      // Far field: Taylor expansion of the dipole kernel r / (4 pi |r|^3) about the node centre.
      const double inv_r = 1.0 / std::sqrt(dist2);
      const double inv_r2 = inv_r * inv_r;
      const double inv_r3 = inv_r * inv_r2;
      const double inv_r5 = inv_r3 * inv_r2;
      const double inv_r7 = inv_r5 * inv_r2;
      const double term0 = r.dot(node.order0) * inv_r3;
      const double term1 = node.order1.trace() * inv_r3 - 3.0 * r.dot(node.order1 * r) * inv_r5;
      double s1 = 0.0, s2 = 0.0, s3 = 0.0;
      for (int i = 0; i < 3; ++i) {
        s1 += node.order2[i].row(i).dot(r.transpose());
        s2 += r[i] * node.order2[i].trace();
        s3 += r[i] * r.dot(node.order2[i] * r);
      }
      const double term2 = 0.5 * (-3.0 * (2.0 * s1 + s2) * inv_r5 + 15.0 * s3 * inv_r7);
      sum += (term0 + term1 + term2) * inv_4pi;
      continue;
    }
    if (node.count > 0) {
      double angle = 0.0;
      for (int t = node.first; t < node.first + node.count; ++t)
        angle += triangle_solid_angle(q, m_a[t], m_b[t], m_c[t]);
      sum += angle * inv_4pi;
      continue;
    }
    stack[top++] = node.right;
    stack[top++] = node.first;
  }
  return sum;
}

double WindingNumber::evaluate(const Vec3& q) const {
  if (m_nodes.empty()) return 0.0;
  return evaluate_node(0, q);
}

std::vector<double> WindingNumber::evaluate_batch(const std::vector<Vec3>& points) const {
  std::vector<double> values(points.size());
  parallel_for(
      0, points.size(), [&](std::size_t i) { values[i] = evaluate(points[i]); }, 64);
  return values;
}

std::vector<bool> WindingNumber::inside_batch(const std::vector<Vec3>& points, double threshold) const {
  const std::vector<double> values = evaluate_batch(points);
  std::vector<bool> inside(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) inside[i] = values[i] > threshold;
  return inside;
}

}  // namespace forensim
