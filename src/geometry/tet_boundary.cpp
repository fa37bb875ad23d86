#include "geometry/tet_boundary.hpp"

#include <algorithm>

namespace forensim {
namespace {

struct FaceKey {
  std::array<Index, 3> sorted;
  Index tet;
  int local_face;
};

std::vector<FaceKey> sorted_faces(const TetMesh& mesh) {
  std::vector<FaceKey> faces;
  faces.reserve(mesh.tets.size() * 4);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    for (int f = 0; f < 4; ++f) {
      std::array<Index, 3> key{mesh.tets[t][tet_local_faces[f][0]], mesh.tets[t][tet_local_faces[f][1]],
                               mesh.tets[t][tet_local_faces[f][2]]};
      std::sort(key.begin(), key.end());
      faces.push_back({key, static_cast<Index>(t), f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const FaceKey& a, const FaceKey& b) {
    return a.sorted != b.sorted ? a.sorted < b.sorted : a.tet < b.tet;
  });
  return faces;
}

TetFace make_face(const TetMesh& mesh, Index tet, int local_face) {
  const Tet& k = mesh.tets[tet];
  return {{k[tet_local_faces[local_face][0]], k[tet_local_faces[local_face][1]], k[tet_local_faces[local_face][2]]},
          tet,
          local_face};
}

}  // namespace

std::vector<TetFace> tet_boundary_faces(const TetMesh& mesh, int label) {
  const std::vector<FaceKey> faces = sorted_faces(mesh);
  std::vector<TetFace> out;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].sorted == faces[i].sorted) ++j;
    if (j - i == 1) {
      if (label < 0 || mesh.label(faces[i].tet) == label)
        out.push_back(make_face(mesh, faces[i].tet, faces[i].local_face));
    } else if (label >= 0 && j - i == 2) {
      const bool in0 = mesh.label(faces[i].tet) == label, in1 = mesh.label(faces[i + 1].tet) == label;
      if (in0 && !in1) out.push_back(make_face(mesh, faces[i].tet, faces[i].local_face));
      if (in1 && !in0) out.push_back(make_face(mesh, faces[i + 1].tet, faces[i + 1].local_face));
    }
    i = j;
  }
  // Deterministic order: by tet, then local face.
  std::sort(out.begin(), out.end(), [](const TetFace& a, const TetFace& b) {
    return a.tet != b.tet ? a.tet < b.tet : a.local_face < b.local_face;
  });
  return out;
}

TriMesh tet_boundary_mesh(const TetMesh& mesh, int label, std::vector<TetFace>* face_source,
                          std::vector<Index>* node_of_vertex) {
  const std::vector<TetFace> faces = tet_boundary_faces(mesh, label);
  TriMesh out;
  std::vector<Index> vmap(mesh.positions.size(), -1);
  std::vector<Index> nodes;
  for (const TetFace& f : faces) {
    Tri t = f.vertices;
    for (Index& i : t) {
      if (vmap[i] < 0) {
        vmap[i] = static_cast<Index>(nodes.size());
        nodes.push_back(i);
        out.positions.push_back(mesh.positions[i]);
      }
      i = vmap[i];
    }
    out.triangles.push_back(t);
  }
  for (const auto& [name, values] : mesh.vertex_fields.scalars) {
    auto& dst = out.vertex_fields.scalars[name];
    for (Index n : nodes) dst.push_back(values[n]);
  }
  for (const auto& [name, values] : mesh.vertex_fields.vectors) {
    auto& dst = out.vertex_fields.vectors[name];
    for (Index n : nodes) dst.push_back(values[n]);
  }
  if (face_source) *face_source = faces;
  if (node_of_vertex) *node_of_vertex = std::move(nodes);
  return out;
}

std::vector<std::array<Index, 4>> tet_neighbors(const TetMesh& mesh) {
  std::vector<std::array<Index, 4>> neighbors(mesh.tets.size(), {-1, -1, -1, -1});
  const std::vector<FaceKey> faces = sorted_faces(mesh);
  for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
    if (faces[i].sorted == faces[i + 1].sorted) {
      neighbors[faces[i].tet][faces[i].local_face] = faces[i + 1].tet;
      neighbors[faces[i + 1].tet][faces[i + 1].local_face] = faces[i].tet;
    }
  }
  return neighbors;
}

}  // namespace forensim
