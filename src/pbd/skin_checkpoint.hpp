#pragma once
/// The binary checkpoint of a skin simulation's State (pbd/skin_simulation.hpp), so that a run interrupted and
/// resumed continues bit-identically: positions, velocities and the last step's tracking points as float64,
/// with the time and step count. Version 1 layout (little-endian as the machine writes it): magic "FSSKINS1",
/// u32 version, f64 time_s, i64 step_count, u64 #S, u64 number of tracking points (0 or #S), then #S positions,
/// #S velocities and the tracking points, 3 f64 each.

#include <string>

#include "pbd/skin_simulation.hpp"

namespace forensim {

/// The checkpoint bytes of `state` (positions and velocities of the same size; tracking points empty or of
/// that size). Throws InputError for mismatched sizes.
std::string skin_state_bytes(const SkinState& state);

/// Reads back skin_state_bytes(); `vertex_count` is the skin model's #S, `source` names the bytes in errors.
/// Throws InputError naming the byte for a malformed, mismatched or non-finite checkpoint.
SkinState skin_state_from_bytes(const std::string& bytes, std::size_t vertex_count, const std::string& source);

}  // namespace forensim
