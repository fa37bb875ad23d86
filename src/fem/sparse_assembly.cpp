#include "fem/sparse_assembly.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {

std::vector<std::vector<Index>> colour_elements(const std::vector<Tet>& elements, std::size_t node_count) {
  // node -> elements, then smallest colour unused by any earlier element sharing a node.
  std::vector<Index> start(node_count + 1, 0);
  for (const Tet& t : elements) {
    for (Index n : t) ++start[static_cast<std::size_t>(n) + 1];
  }
  for (std::size_t i = 0; i < node_count; ++i) start[i + 1] += start[i];
  std::vector<Index> node_elements(static_cast<std::size_t>(start[node_count]));
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (Index n : elements[e])
      node_elements[static_cast<std::size_t>(fill[static_cast<std::size_t>(n)]++)] = static_cast<Index>(e);
  }
  std::vector<int> colour(elements.size(), -1);
  std::vector<std::size_t> stamp;  // stamp[c] == e + 1 when colour c is taken by a neighbour of e
  std::vector<std::vector<Index>> colours;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (Index n : elements[e]) {
      for (Index k = start[static_cast<std::size_t>(n)]; k < start[static_cast<std::size_t>(n) + 1]; ++k) {
        const int c = colour[static_cast<std::size_t>(node_elements[static_cast<std::size_t>(k)])];
        if (c >= 0) stamp[static_cast<std::size_t>(c)] = e + 1;
      }
    }
    std::size_t c = 0;
    while (c < stamp.size() && stamp[c] == e + 1) ++c;
    if (c == stamp.size()) {
      stamp.push_back(0);
      colours.emplace_back();
    }
    colour[e] = static_cast<int>(c);
    colours[c].push_back(static_cast<Index>(e));
  }
  return colours;
}

SparsityPattern::SparsityPattern(const std::vector<Tet>& elements, std::size_t node_count, int block_size)
    : m_block_size(block_size), m_node_count(node_count), m_elements(elements) {
  if (block_size != 1 && block_size != 3) throw NumericError("SparsityPattern: block size must be 1 or 3");
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (Index n : elements[e]) {
      if (n < 0 || static_cast<std::size_t>(n) >= node_count) {
        throw InputError("sparsity pattern", "element " + std::to_string(e),
                         "node index " + std::to_string(n) + " out of range");
      }
    }
  }
  // Sorted neighbour lists (including the node itself).
  std::vector<std::vector<Index>> neighbours(node_count);
  for (std::size_t n = 0; n < node_count; ++n) neighbours[n].push_back(static_cast<Index>(n));
  for (const Tet& t : elements) {
    for (Index a : t) {
      for (Index b : t) {
        if (a != b) neighbours[static_cast<std::size_t>(a)].push_back(b);
      }
    }
  }
  parallel_for(0, node_count, [&](std::size_t n) {
    auto& list = neighbours[n];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  });
  const std::ptrdiff_t bs = block_size;
  const std::size_t dofs = node_count * static_cast<std::size_t>(block_size);
  std::vector<std::ptrdiff_t> outer(dofs + 1, 0);
  for (std::size_t n = 0; n < node_count; ++n) {
    const std::ptrdiff_t column_nnz = bs * static_cast<std::ptrdiff_t>(neighbours[n].size());
    for (int c = 0; c < block_size; ++c) {
      const std::size_t col = n * static_cast<std::size_t>(block_size) + static_cast<std::size_t>(c);
      outer[col + 1] = outer[col] + column_nnz;
    }
  }
  const std::ptrdiff_t nnz = outer[dofs];
  if (nnz > std::numeric_limits<int>::max()) throw NumericError("SparsityPattern: too many nonzeros for int indices");
  m_structure.resize(static_cast<Eigen::Index>(dofs), static_cast<Eigen::Index>(dofs));
  m_structure.resizeNonZeros(static_cast<Eigen::Index>(nnz));
  int* outer_ptr = m_structure.outerIndexPtr();
  int* inner_ptr = m_structure.innerIndexPtr();
  for (std::size_t i = 0; i <= dofs; ++i) outer_ptr[i] = static_cast<int>(outer[i]);
  parallel_for(0, node_count, [&](std::size_t n) {
    for (int c = 0; c < block_size; ++c) {
      std::ptrdiff_t k = outer[n * static_cast<std::size_t>(block_size) + static_cast<std::size_t>(c)];
      for (Index m : neighbours[n]) {
        for (int r = 0; r < block_size; ++r) inner_ptr[k++] = static_cast<int>(m * block_size + r);
      }
    }
  });
  std::fill(m_structure.valuePtr(), m_structure.valuePtr() + nnz, 0.0);

  m_element_entries.resize(elements.size());
  parallel_for(0, elements.size(), [&](std::size_t e) {
    const Tet& t = elements[e];
    for (int b = 0; b < 4; ++b) {
      const auto& list = neighbours[static_cast<std::size_t>(t[b])];
      const std::ptrdiff_t col_start = outer[static_cast<std::size_t>(t[b]) * static_cast<std::size_t>(block_size)];
      for (int a = 0; a < 4; ++a) {
        const auto it = std::lower_bound(list.begin(), list.end(), t[a]);
        m_element_entries[e][static_cast<std::size_t>(4 * a + b)] = col_start + bs * (it - list.begin());
      }
    }
  });
  m_diagonal.resize(dofs);
  for (std::size_t d = 0; d < dofs; ++d) m_diagonal[d] = entry(static_cast<Index>(d), static_cast<Index>(d));
  m_colours = colour_elements(elements, node_count);
}

std::ptrdiff_t SparsityPattern::entry(Index row, Index col) const {
  if (row < 0 || col < 0 || static_cast<std::size_t>(row) >= dof_count() ||
      static_cast<std::size_t>(col) >= dof_count()) {
    return -1;
  }
  const int* inner = m_structure.innerIndexPtr();
  const int begin = m_structure.outerIndexPtr()[col];
  const int end = m_structure.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(inner + begin, inner + end, row);
  return (it != inner + end && *it == row) ? (it - inner) : -1;
}

void SparsityPattern::check_matrix(const SparseMatrix& out, int block_size) const {
  if (m_block_size != block_size || out.nonZeros() != m_structure.nonZeros() || out.rows() != m_structure.rows() ||
      !out.isCompressed()) {
    throw NumericError("SparsityPattern: matrix does not have this pattern (use make_matrix)");
  }
}

void SparsityPattern::assemble_scalar(const std::function<void(std::size_t, Mat4&)>& element, SparseMatrix& out) const {
  check_matrix(out, 1);
  double* values = out.valuePtr();
  std::fill(values, values + out.nonZeros(), 0.0);
  for (const auto& colour : m_colours) {
    parallel_for(
        0, colour.size(),
        [&](std::size_t i) {
          const auto e = static_cast<std::size_t>(colour[i]);
          Mat4 ke;
          element(e, ke);
          const auto& entries = m_element_entries[e];
          for (int a = 0; a < 4; ++a) {
            for (int b = 0; b < 4; ++b) values[entries[static_cast<std::size_t>(4 * a + b)]] += ke(a, b);
          }
        },
        64);
  }
}

void SparsityPattern::assemble_block(const std::function<void(std::size_t, Mat12&)>& element, SparseMatrix& out) const {
  check_matrix(out, 3);
  double* values = out.valuePtr();
  const int* outer = out.outerIndexPtr();
  std::fill(values, values + out.nonZeros(), 0.0);
  for (const auto& colour : m_colours) {
    parallel_for(
        0, colour.size(),
        [&](std::size_t i) {
          const auto e = static_cast<std::size_t>(colour[i]);
          Mat12 ke;
          element(e, ke);
          const auto& entries = m_element_entries[e];
          const Tet& t = m_elements[e];
          for (int b = 0; b < 4; ++b) {
            const int col0 = 3 * t[static_cast<std::size_t>(b)];
            const std::ptrdiff_t stride = outer[col0 + 1] - outer[col0];
            for (int a = 0; a < 4; ++a) {
              const std::ptrdiff_t base = entries[static_cast<std::size_t>(4 * a + b)];
              for (int c = 0; c < 3; ++c) {
                double* column = values + base + c * stride;
                for (int r = 0; r < 3; ++r) column[r] += ke(3 * a + r, 3 * b + c);
              }
            }
          }
        },
        32);
  }
}

}  // namespace forensim
