#include "pbd/skin_checkpoint.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/error.hpp"

namespace forensim {
namespace {

constexpr char magic[8] = {'F', 'S', 'S', 'K', 'I', 'N', 'S', '1'};
constexpr std::size_t header = 8 + 4 + 8 + 8 + 8 + 8;

template <typename T>
void put(std::string& out, const T& value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

template <typename T>
T get(const std::string& in, std::size_t& offset) {
  T value;
  std::memcpy(&value, in.data() + offset, sizeof(T));
  offset += sizeof(T);
  return value;
}

void put_points(std::string& out, const std::vector<Vec3>& points) {
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) put<double>(out, p[k]);
}

void get_points(const std::string& in, std::size_t& offset, std::size_t count, std::vector<Vec3>& points) {
  points.resize(count);
  for (Vec3& p : points)
    for (int k = 0; k < 3; ++k) p[k] = get<double>(in, offset);
}

}  // namespace

std::string skin_state_bytes(const SkinState& state) {
  const std::size_t n = state.positions.size();
  require_input(state.velocities.size() == n && (state.tracking_points.empty() || state.tracking_points.size() == n),
                "skin checkpoint", "state",
                std::to_string(n) + " positions, " + std::to_string(state.velocities.size()) + " velocities and " +
                    std::to_string(state.tracking_points.size()) + " tracking points do not match");
  std::string out;
  out.reserve(header + (2 * n + state.tracking_points.size()) * 3 * sizeof(double));
  out.append(magic, 8);
  put<std::uint32_t>(out, 1);
  put<double>(out, state.time_s);
  put<std::int64_t>(out, state.step_count);
  put<std::uint64_t>(out, n);
  put<std::uint64_t>(out, state.tracking_points.size());
  put_points(out, state.positions);
  put_points(out, state.velocities);
  put_points(out, state.tracking_points);
  return out;
}

SkinState skin_state_from_bytes(const std::string& in, std::size_t vertex_count, const std::string& source) {
  require_input(in.size() >= header, source, "byte 0", "too short for a skin checkpoint");
  require_input(std::memcmp(in.data(), magic, 8) == 0, source, "byte 0", "not a skin checkpoint");
  std::size_t offset = 8;
  const auto version = get<std::uint32_t>(in, offset);
  require_input(version == 1, source, "byte 8", "unknown skin checkpoint version " + std::to_string(version));
  SkinState state;
  state.time_s = get<double>(in, offset);
  state.step_count = get<std::int64_t>(in, offset);
  const auto n = get<std::uint64_t>(in, offset);
  const auto tracked = get<std::uint64_t>(in, offset);
  require_input(n == vertex_count, source, "byte 28",
                "skin checkpoint has " + std::to_string(n) + " vertices, the skin " + std::to_string(vertex_count));
  require_input(tracked == 0 || tracked == n, source, "byte 36",
                std::to_string(tracked) + " tracking points for " + std::to_string(n) + " vertices");
  require_input(in.size() == header + (2 * n + tracked) * 3 * sizeof(double), source,
                "byte " + std::to_string(in.size()), "size does not match the vertex count");
  require_input(std::isfinite(state.time_s) && state.time_s >= 0.0 && state.step_count >= 0, source, "byte 12",
                "bad time or step count");
  get_points(in, offset, n, state.positions);
  get_points(in, offset, n, state.velocities);
  get_points(in, offset, tracked, state.tracking_points);
  for (std::size_t i = 0; i < n; ++i)
    require_input(state.positions[i].allFinite() && state.velocities[i].allFinite() &&
                      (tracked == 0 || state.tracking_points[i].allFinite()),
                  source, "skin vertex " + std::to_string(i), "non-finite value");
  return state;
}

}  // namespace forensim
