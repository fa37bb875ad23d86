#pragma once
/// The checkpoint of a `forensim mummify` run (checkpoint.bin in the run folder), written at every output frame
/// and on interruption, so `--resume` continues bit-identically: the desiccation state (moisture, shape,
/// time) and the skin motion's state (the position-based skin's positions, velocities and tracking points) in
/// one file, written atomically, so the two can never disagree. Layout: magic "FSMUMMY1", u64 number of skins,
/// then sections, each a u64 byte count and its bytes: desiccation_checkpoint_bytes(), then one
/// MummifySkinMotion::checkpoint_bytes() per skin (the run's skin, then the Figure 8 comparison skins, if any;
/// empty for a skin glued to the volume).

#include <filesystem>
#include <string>
#include <vector>

#include "desiccation/desiccation_sim.hpp"

namespace forensim::cli {

struct MummifyCheckpoint {
  DesiccationState state;
  std::vector<std::string> skins;  ///< MummifySkinMotion::checkpoint_bytes() per skin
};

/// Writes the checkpoint atomically. Throws IoError.
void write_mummify_checkpoint(const std::filesystem::path& path, const DesiccationState& state,
                              const std::vector<std::string>& skins);

/// Reads a checkpoint of a run whose volume has `vertex_count` nodes. Throws InputError naming the file and byte
/// for a malformed or mismatched file, IoError when it cannot be read.
MummifyCheckpoint read_mummify_checkpoint(const std::filesystem::path& path, std::size_t vertex_count);

}  // namespace forensim::cli
