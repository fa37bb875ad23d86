#pragma once
/// Little helpers of the project's binary checkpoints: plain values appended to and read from a byte string
/// in the host's byte order (the checkpoints are read back on the machine that wrote them). Readers check the
/// record's size before reading; these helpers do not.

#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/types.hpp"

namespace forensim::bytes {

/// Appends the bytes of `value`.
template <typename T>
void append(std::string& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

/// Reads a T at `offset` and advances it (the caller has checked that sizeof(T) bytes are there).
template <typename T>
T read(const std::string& in, std::size_t& offset) {
  static_assert(std::is_trivially_copyable_v<T>);
  T value;
  std::memcpy(&value, in.data() + offset, sizeof(T));
  offset += sizeof(T);
  return value;
}

/// Appends each point as three float64.
inline void append_points(std::string& out, const std::vector<Vec3>& points) {
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) append<double>(out, p[k]);
}

/// Reads `count` points of three float64 at `offset` into `points` and advances `offset`.
inline void read_points(const std::string& in, std::size_t& offset, std::size_t count, std::vector<Vec3>& points) {
  points.resize(count);
  for (Vec3& p : points)
    for (int k = 0; k < 3; ++k) p[k] = read<double>(in, offset);
}

}  // namespace forensim::bytes
