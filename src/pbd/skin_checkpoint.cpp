#include "pbd/skin_checkpoint.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/byte_record.hpp"
#include "core/error.hpp"

namespace forensim {
namespace {

constexpr char magic[8] = {'F', 'S', 'S', 'K', 'I', 'N', 'S', '1'};
constexpr std::size_t header = 8 + 4 + 8 + 8 + 8 + 8;

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
  bytes::append<std::uint32_t>(out, 1);
  bytes::append<double>(out, state.time_s);
  bytes::append<std::int64_t>(out, state.step_count);
  bytes::append<std::uint64_t>(out, n);
  bytes::append<std::uint64_t>(out, state.tracking_points.size());
  bytes::append_points(out, state.positions);
  bytes::append_points(out, state.velocities);
  bytes::append_points(out, state.tracking_points);
  return out;
}

SkinState skin_state_from_bytes(const std::string& in, std::size_t vertex_count, const std::string& source) {
  require_input(in.size() >= header, source, "byte 0", "too short for a skin checkpoint");
  require_input(std::memcmp(in.data(), magic, 8) == 0, source, "byte 0", "not a skin checkpoint");
  std::size_t offset = 8;
  const auto version = bytes::read<std::uint32_t>(in, offset);
  require_input(version == 1, source, "byte 8", "unknown skin checkpoint version " + std::to_string(version));
  SkinState state;
  state.time_s = bytes::read<double>(in, offset);
  state.step_count = bytes::read<std::int64_t>(in, offset);
  const auto n = bytes::read<std::uint64_t>(in, offset);
  const auto tracked = bytes::read<std::uint64_t>(in, offset);
  require_input(n == vertex_count, source, "byte 28",
                "skin checkpoint has " + std::to_string(n) + " vertices, the skin " + std::to_string(vertex_count));
  require_input(tracked == 0 || tracked == n, source, "byte 36",
                std::to_string(tracked) + " tracking points for " + std::to_string(n) + " vertices");
  require_input(in.size() == header + (2 * n + tracked) * 3 * sizeof(double), source,
                "byte " + std::to_string(in.size()), "size does not match the vertex count");
  require_input(std::isfinite(state.time_s) && state.time_s >= 0.0 && state.step_count >= 0, source, "byte 12",
                "bad time or step count");
  bytes::read_points(in, offset, n, state.positions);
  bytes::read_points(in, offset, n, state.velocities);
  bytes::read_points(in, offset, tracked, state.tracking_points);
  for (std::size_t i = 0; i < n; ++i)
    require_input(state.positions[i].allFinite() && state.velocities[i].allFinite() &&
                      (tracked == 0 || state.tracking_points[i].allFinite()),
                  source, "skin vertex " + std::to_string(i), "non-finite value");
  return state;
}

}  // namespace forensim
