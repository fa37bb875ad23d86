#pragma once
/// A run's output folder: self-describing, so any result can be reproduced. Alongside the results it
/// records run.json: the command, the resolved job, forensim's version, the seed, the thread count and
/// the timings of each stage. Files are written atomically.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/timer.hpp"

namespace forensim {

class RunFolder {
 public:
  /// Creates `folder` (and parents). `command` names what runs ("mummify", "demo").
  RunFolder(std::filesystem::path folder, std::string command);

  const std::filesystem::path& path() const { return m_folder; }
  /// Path of an output inside the folder (creates sub-folders).
  std::filesystem::path file(const std::string& relative) const;
  /// Writes an output file atomically and lists it in run.json.
  void write(const std::string& relative, std::string_view bytes);
  /// Lists a file written by other means (through AtomicFile) in run.json.
  void add_output(const std::string& relative);

  void set_job(const nlohmann::json& resolved_job) { m_record["job"] = resolved_job; }
  void set_seed(std::uint64_t seed) { m_record["seed"] = seed; }
  /// Extra facts to keep (counts, measured figures).
  nlohmann::json& facts() { return m_record["facts"]; }
  Timings& timings() { return m_timings; }

  /// Writes run.json (atomically). Call at the end of a run, and after checkpoints.
  void write_record() const;

 private:
  std::filesystem::path m_folder;
  nlohmann::json m_record;
  Timings m_timings;
};

/// forensim's version string ("0.1.0").
std::string version_string();

}  // namespace forensim
