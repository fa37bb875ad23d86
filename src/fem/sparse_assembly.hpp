#pragma once
/// Fixed sparsity pattern of a tetrahedral FEM matrix, built once, and fast deterministic reassembly into
/// it. Solvers reassemble every time step (coefficients, rotations change) while the structure stays, so
/// the symbolic work (sorting, index look-up, a sparse solver's ordering) is done once here.
///
/// Determinism: elements are greedily coloured so that no two elements of a colour share a node. Colours
/// are assembled one after another and the elements of one colour in parallel; each matrix entry thus
/// receives its element contributions in colour order whatever the thread count (no atomics on doubles),
/// and the result is bitwise identical at any thread count.

#include <Eigen/SparseCore>
#include <functional>
#include <vector>

#include "core/types.hpp"
#include "fem/tet_element.hpp"

namespace forensim {

using SparseMatrix = Eigen::SparseMatrix<double>;  ///< column-major, compressed, int indices

class SparsityPattern {
 public:
  SparsityPattern() = default;
  /// Pattern of the matrix coupling every pair of nodes that share an element. `elements`: #E tets of node
  /// indices in [0, node_count). `block_size` 1 (scalar field: one unknown per node) or 3 (displacement:
  /// unknowns 3 n, 3 n + 1, 3 n + 2 of node n). Both triangles are stored (full symmetric storage).
  SparsityPattern(const std::vector<Tet>& elements, std::size_t node_count, int block_size);

  int block_size() const { return m_block_size; }
  std::size_t node_count() const { return m_node_count; }
  std::size_t dof_count() const { return m_node_count * static_cast<std::size_t>(m_block_size); }
  std::size_t element_count() const { return m_elements.size(); }
  std::size_t nonzero_count() const { return static_cast<std::size_t>(m_structure.nonZeros()); }
  /// Element lists of the colours (no two elements of a colour share a node).
  const std::vector<std::vector<Index>>& colours() const { return m_colours; }

  /// A compressed matrix with this structure and all values zero.
  SparseMatrix make_matrix() const { return m_structure; }

  /// Index into the value array of entry (row, col) (dof indices), or -1 if it is not in the pattern.
  std::ptrdiff_t entry(Index row, Index col) const;
  /// Value indices of the diagonal entries, one per dof.
  const std::vector<std::ptrdiff_t>& diagonal_entries() const { return m_diagonal; }

  /// Sets `out` (from make_matrix) to the sum of the elements' 4x4 matrices; `element(e, Ke)` fills Ke for
  /// element e and is called in parallel (must be thread-safe). Block size 1 only.
  void assemble_scalar(const std::function<void(std::size_t, Mat4&)>& element, SparseMatrix& out) const;
  /// Same for 12x12 element matrices (corner-major xyz), block size 3 only.
  void assemble_block(const std::function<void(std::size_t, Mat12&)>& element, SparseMatrix& out) const;

 private:
  void check_matrix(const SparseMatrix& out, int block_size) const;

  int m_block_size = 1;
  std::size_t m_node_count = 0;
  std::vector<Tet> m_elements;
  SparseMatrix m_structure;
  /// Per element and corner pair (a, b): value index of entry (dof(a), dof(b)) where dof is the node's first
  /// unknown. For blocks, column dof(b) + c starts c * (3 deg(b)) further on (all three columns of a node
  /// have the same rows).
  std::vector<std::array<std::ptrdiff_t, 16>> m_element_entries;
  std::vector<std::ptrdiff_t> m_diagonal;
  std::vector<std::vector<Index>> m_colours;
};

/// Greedy colouring of elements so that no two elements of one colour share a node (deterministic: elements
/// visited in order, each given the smallest free colour).
std::vector<std::vector<Index>> colour_elements(const std::vector<Tet>& elements, std::size_t node_count);

}  // namespace forensim
