#include "server/run_index.hpp"

#include <algorithm>
#include <system_error>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "server/served_path.hpp"
#include "tet_io/pvd_writer.hpp"

namespace forensim {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxDescriptionBytes = std::size_t{16} << 20;

nlohmann::json parse_json_file(const fs::path& path) {
  const std::string text = read_file(path, kMaxDescriptionBytes);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path.string(), "byte " + std::to_string(e.byte), "is not valid JSON");
  } catch (const nlohmann::json::exception& e) {  // e.g. a number too large for a double
    throw InputError(path.string(), "", std::string("is not valid JSON: ") + e.what());
  }
}

void scan(const fs::path& root, const fs::path& folder, int depth, nlohmann::json& runs, nlohmann::json& skipped) {
  std::error_code ec;
  const fs::path record = folder / "run.json";
  if (fs::is_regular_file(fs::symlink_status(record, ec))) {
    try {
      const nlohmann::json j = parse_json_file(record);
      if (!j.is_object() || !j.contains("command")) {
        throw InputError(record.string(), "", "is not a forensim run record (no \"command\")");
      }
      nlohmann::json entry;
      entry["path"] = served_relative(root, folder);
      entry["command"] = j["command"];
      for (const char* key : {"started_utc", "forensim_version", "facts"}) {
        if (j.contains(key)) entry[key] = j[key];
      }
      runs.push_back(entry);
    } catch (const Error& e) {
      skipped.push_back({{"path", served_relative(root, folder)}, {"reason", e.what()}});
    }
  }
  if (depth <= 0) return;
  std::vector<fs::path> children;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::file_status s = it->symlink_status(ec);
    if (!ec && fs::is_directory(s) && it->path().filename().string().front() != '.') children.push_back(it->path());
  }
  std::sort(children.begin(), children.end());
  for (const fs::path& child : children) scan(root, child, depth - 1, runs, skipped);
}

}  // namespace

nlohmann::json list_runs(const fs::path& root, int max_depth) {
  nlohmann::json runs = nlohmann::json::array(), skipped = nlohmann::json::array();
  std::error_code ec;
  const fs::path real_root = fs::canonical(root, ec);
  if (ec) throw IoError(root.string(), "served folder does not exist");
  scan(real_root, real_root, max_depth, runs, skipped);
  return {{"runs", runs}, {"skipped", skipped}};
}

nlohmann::json describe_run(const fs::path& root, const fs::path& folder) {
  const fs::path record_path = folder / "run.json";
  std::error_code ec;
  if (!fs::is_regular_file(record_path, ec)) throw IoError(record_path.string(), "no run.json: not a run folder");
  nlohmann::json out;
  out["path"] = served_relative(root, folder);
  out["record"] = parse_json_file(record_path);
  const std::string command = out["record"].value("command", "");
  out["kind"] = command;
  nlohmann::json files = nlohmann::json::array();
  std::vector<std::pair<std::string, std::uintmax_t>> found;
  for (fs::recursive_directory_iterator it(folder, fs::directory_options::none, ec), end; !ec && it != end;
       it.increment(ec)) {
    if (it.depth() > 3) it.disable_recursion_pending();
    const fs::file_status s = it->symlink_status(ec);
    if (ec || !fs::is_regular_file(s)) continue;
    const std::string name = it->path().filename().string();
    if (name.rfind(".tmp-", 0) == 0) continue;  // an atomic write in progress
    found.emplace_back(it->path().lexically_relative(folder).generic_string(), it->file_size(ec));
  }
  std::sort(found.begin(), found.end());
  for (const auto& [path, bytes] : found) files.push_back({{"path", path}, {"bytes", bytes}});
  out["files"] = files;
  if (fs::is_regular_file(folder / "timeline.json", ec)) out["timeline"] = parse_json_file(folder / "timeline.json");
  // A mummify run's series: the volume's frames and the skin's (the same times).
  for (const auto& [series, key] : {std::pair{"desiccation.pvd", "frames"}, std::pair{"skin.pvd", "skin_frames"}}) {
    if (!fs::is_regular_file(folder / series, ec)) continue;
    nlohmann::json frames = nlohmann::json::array();
    for (const PvdEntry& e : read_pvd(folder / series)) frames.push_back({{"time_days", e.time}, {"file", e.file}});
    out[key] = frames;
  }
  return out;
}

}  // namespace forensim
