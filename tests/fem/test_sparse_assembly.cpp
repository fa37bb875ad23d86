#include <gtest/gtest.h>

#include <set>

#include "core/parallel.hpp"
#include "fem/sparse_assembly.hpp"
#include "geometry/primitives.hpp"

using namespace forensim;

namespace {

Mat4 scalar_element(std::size_t e) {
  Mat4 m;
  for (int a = 0; a < 4; ++a) {
    for (int b = 0; b < 4; ++b) m(a, b) = 1.0 + 0.001 * static_cast<double>(e) + 0.1 * a + 0.37 * b;
  }
  return m;
}

Mat12 block_element(std::size_t e) {
  Mat12 m;
  for (int a = 0; a < 12; ++a) {
    for (int b = 0; b < 12; ++b) m(a, b) = std::sin(0.01 * static_cast<double>(e) + a * 0.3 + b * 0.71);
  }
  return m;
}

}  // namespace

TEST(SparseAssembly, ColoursAreIndependentAndCoverAllElements) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3::Ones(), 4, 3, 5);
  const auto colours = colour_elements(mesh.tets, mesh.vertex_count());
  std::size_t total = 0;
  for (const auto& colour : colours) {
    std::set<Index> nodes;
    for (Index e : colour) {
      for (Index n : mesh.tets[static_cast<std::size_t>(e)]) EXPECT_TRUE(nodes.insert(n).second);
    }
    total += colour.size();
  }
  EXPECT_EQ(total, mesh.tet_count());
}

TEST(SparseAssembly, ScalarAssemblyMatchesTriplets) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3::Ones(), 3, 4, 2);
  const SparsityPattern pattern(mesh.tets, mesh.vertex_count(), 1);
  SparseMatrix a = pattern.make_matrix();
  pattern.assemble_scalar([](std::size_t e, Mat4& m) { m = scalar_element(e); }, a);
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    const Mat4 m = scalar_element(e);
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) triplets.emplace_back(mesh.tets[e][i], mesh.tets[e][j], m(i, j));
    }
  }
  SparseMatrix b(a.rows(), a.cols());
  b.setFromTriplets(triplets.begin(), triplets.end());
  EXPECT_LT((a - b).norm(), 1e-12 * b.norm());
  EXPECT_EQ(pattern.entry(0, static_cast<Index>(mesh.vertex_count() - 1)), -1);
  EXPECT_GE(pattern.entry(0, 0), 0);
}

TEST(SparseAssembly, BlockAssemblyMatchesTripletsAndIsThreadIndependent) {
  const TetMesh mesh = make_box_tet_mesh(Vec3::Zero(), Vec3::Ones(), 5, 4, 4);
  const SparsityPattern pattern(mesh.tets, mesh.vertex_count(), 3);
  EXPECT_EQ(pattern.dof_count(), 3 * mesh.vertex_count());
  SparseMatrix a = pattern.make_matrix();
  set_thread_count(1);
  pattern.assemble_block([](std::size_t e, Mat12& m) { m = block_element(e); }, a);
  set_thread_count(2);
  SparseMatrix a2 = pattern.make_matrix();
  pattern.assemble_block([](std::size_t e, Mat12& m) { m = block_element(e); }, a2);
  set_thread_count(0);
  for (Eigen::Index k = 0; k < a.nonZeros(); ++k) ASSERT_EQ(a.valuePtr()[k], a2.valuePtr()[k]);
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t e = 0; e < mesh.tet_count(); ++e) {
    const Mat12 m = block_element(e);
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < 12; ++j)
        triplets.emplace_back(3 * mesh.tets[e][i / 3] + i % 3, 3 * mesh.tets[e][j / 3] + j % 3, m(i, j));
    }
  }
  SparseMatrix b(a.rows(), a.cols());
  b.setFromTriplets(triplets.begin(), triplets.end());
  EXPECT_LT((a - b).norm(), 1e-12 * b.norm());
}

TEST(SparseAssembly, RejectsOutOfRangeNodes) {
  std::vector<Tet> tets = {Tet{0, 1, 2, 7}};
  EXPECT_THROW(SparsityPattern(tets, 4, 1), std::exception);
}
