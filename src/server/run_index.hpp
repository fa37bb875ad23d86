#pragma once
/// The runs a served folder holds: every folder (the root included, down to a few levels) with a run.json
/// record that a forensim command wrote (see core/run_folder.hpp), and the files inside one run.

#include <nlohmann/json.hpp>

#include <filesystem>

namespace forensim {

/// Runs under `root`, searched `max_depth` folder levels deep (0: the root only), in path order. Each entry:
/// {"path": relative folder ("" for the root), "command": "wound" | "mummify" | ..., "started_utc",
///  "forensim_version", "facts"}. Folders that cannot be read and malformed run.json files are skipped
/// (listed under "skipped" with the reason) rather than failing the whole listing. Symbolic links are not
/// followed.
nlohmann::json list_runs(const std::filesystem::path& root, int max_depth = 3);

/// One run: {"path", "record": run.json, "files": [{"path", "bytes"}], "kind": "wound" | "mummify" | other,
/// plus for wound runs "timeline" (timeline.json) and for mummify runs "frames": [{"time_days", "file"}]
/// from desiccation.pvd (the volume) and "skin_frames" in the same form from skin.pvd (the skin), when present}.
/// `folder` is the resolved run folder inside `root`. Throws InputError when run.json or a listed description file is
/// malformed, IoError when they cannot be read.
nlohmann::json describe_run(const std::filesystem::path& root, const std::filesystem::path& folder);

}  // namespace forensim
