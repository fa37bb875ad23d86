#pragma once
/// Shared fixtures of the tet_io tests: a labelled box tet mesh with vertex and tet fields, and comparisons.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "geometry/primitives.hpp"
#include "geometry/tet_mesh.hpp"

namespace forensim::test {

/// Box tet mesh (nx*ny*nz cubes, 6 tets each) with labels flesh/bone/7 and fields whose values have no
/// short decimal form, so any precision loss shows.
inline TetMesh sample_tet_mesh(int nx = 3, int ny = 2, int nz = 2) {
  TetMesh mesh = make_box_tet_mesh(Vec3(-0.1, 0.3, 1.0 / 3.0), Vec3(1.1, 2.3, 1.7), nx, ny, nz);
  mesh.tet_labels.resize(mesh.tet_count());
  std::vector<double> shrinkage(mesh.tet_count());
  std::vector<Vec3> stress(mesh.tet_count());
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    Vec3 c = Vec3::Zero();
    for (Index v : mesh.tets[t]) c += mesh.positions[v] / 4.0;
    mesh.tet_labels[t] = c.x() < 0.4 ? tissue_bone : (c.y() > 1.9 ? 7 : tissue_flesh);
    shrinkage[t] = std::sqrt(static_cast<double>(t) + 0.5) / 3.0;
    stress[t] = Vec3(c.x() / 7.0, -c.y() * 1e-9, std::exp(c.z()));
  }
  std::vector<double> moisture(mesh.vertex_count());
  std::vector<Vec3> displacement(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3& p = mesh.positions[v];
    moisture[v] = std::sin(p.x()) + p.y() / 3.0 + 1e-12 * p.z();
    displacement[v] = Vec3(0.1 * p.x() / 3.0, p.y() * p.y() / 7.0, -p.z() / 11.0);
  }
  mesh.vertex_fields.scalars["moisture"] = moisture;
  mesh.vertex_fields.vectors["displacement"] = displacement;
  mesh.tet_fields.scalars["shrinkage"] = shrinkage;
  mesh.tet_fields.vectors["stress"] = stress;
  return mesh;
}

/// Rounds to what a Float32 array holds.
inline double as_float(double v) {
  return static_cast<double>(static_cast<float>(v));
}

/// Exact topology, labels (by label()), and positions equal after rounding through float when `float32`.
inline void expect_same_geometry(const TetMesh& expected, const TetMesh& actual, bool float32 = false) {
  ASSERT_EQ(actual.vertex_count(), expected.vertex_count());
  ASSERT_EQ(actual.tet_count(), expected.tet_count());
  for (std::size_t t = 0; t < expected.tet_count(); ++t) {
    ASSERT_EQ(actual.tets[t], expected.tets[t]) << "tet " << t;
    ASSERT_EQ(actual.label(t), expected.label(t)) << "tet " << t;
  }
  for (std::size_t v = 0; v < expected.vertex_count(); ++v) {
    for (int k = 0; k < 3; ++k) {
      const double e = float32 ? as_float(expected.positions[v][k]) : expected.positions[v][k];
      ASSERT_EQ(actual.positions[v][k], e) << "node " << v;
    }
  }
}

/// Every field present with the same values (exact, or exact after rounding through float).
inline void expect_same_fields(const FieldSet& expected, const FieldSet& actual, bool float32 = false) {
  ASSERT_EQ(actual.scalars.size(), expected.scalars.size());
  ASSERT_EQ(actual.vectors.size(), expected.vectors.size());
  for (const auto& [name, values] : expected.scalars) {
    ASSERT_TRUE(actual.scalars.count(name)) << name;
    const auto& got = actual.scalars.at(name);
    ASSERT_EQ(got.size(), values.size()) << name;
    for (std::size_t i = 0; i < values.size(); ++i) {
      ASSERT_EQ(got[i], float32 ? as_float(values[i]) : values[i]) << name << "[" << i << "]";
    }
  }
  for (const auto& [name, values] : expected.vectors) {
    ASSERT_TRUE(actual.vectors.count(name)) << name;
    const auto& got = actual.vectors.at(name);
    ASSERT_EQ(got.size(), values.size()) << name;
    for (std::size_t i = 0; i < values.size(); ++i) {
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(got[i][k], float32 ? as_float(values[i][k]) : values[i][k]) << name << "[" << i << "]";
      }
    }
  }
}

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void spit(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

}  // namespace forensim::test
