#include "core/run_folder.hpp"

#include <chrono>
#include <ctime>
#include <system_error>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "forensim/config.hpp"

namespace forensim {

std::string version_string() {
  return FORENSIM_VERSION_STRING;
}

RunFolder::RunFolder(std::filesystem::path folder, std::string command) : m_folder(std::move(folder)) {
  std::error_code ec;
  std::filesystem::create_directories(m_folder, ec);
  if (ec) throw IoError(m_folder.string(), "cannot create output folder: " + ec.message());
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  m_record["command"] = std::move(command);
  m_record["forensim_version"] = version_string();
  m_record["started_utc"] = stamp;
  m_record["threads"] = thread_count();
  m_record["outputs"] = nlohmann::json::array();
  m_record["facts"] = nlohmann::json::object();
}

std::filesystem::path RunFolder::file(const std::string& relative) const {
  const std::filesystem::path p = m_folder / relative;
  std::error_code ec;
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
  if (ec) throw IoError(p.parent_path().string(), "cannot create folder: " + ec.message());
  return p;
}

void RunFolder::add_output(const std::string& relative) {
  for (const auto& o : m_record["outputs"]) {
    if (o == relative) return;
  }
  m_record["outputs"].push_back(relative);
}

void RunFolder::write(const std::string& relative, std::string_view bytes) {
  write_file_atomic(file(relative), bytes);
  add_output(relative);
}

void RunFolder::write_record() const {
  nlohmann::json record = m_record;
  nlohmann::json timings = nlohmann::json::object();
  for (const auto& [stage, seconds] : m_timings.stages()) timings[stage] = seconds;
  record["timings_s"] = timings;
  write_file_atomic(m_folder / "run.json", record.dump(2) + "\n");
}

}  // namespace forensim
