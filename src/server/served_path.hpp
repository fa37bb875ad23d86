#pragma once
/// Paths inside a served folder. Every file `forensim serve` reads on behalf of a request goes through
/// resolve_served_path(), so no request reaches a file outside the folders it serves: absolute paths, ".."
/// components, NUL bytes and backslashes are refused outright, and what remains is resolved with its
/// symbolic links followed and must still lie inside the (resolved) root.

#include <filesystem>
#include <string>

namespace forensim {

/// Why a relative path was refused.
enum class ServedPathProblem {
  none,
  malformed,  ///< empty where a file is needed, absolute, "..", NUL, backslash, or too long
  outside,    ///< resolves (through a symbolic link) outside the root
  missing,    ///< inside the root but does not exist
};

struct ServedPath {
  std::filesystem::path path;  ///< resolved absolute path (valid when problem == none)
  ServedPathProblem problem = ServedPathProblem::none;
  std::string message;  ///< what is wrong, naming the request path
};

/// Resolves `relative` (a '/'-separated path from a request, already URL-decoded) against `root`.
/// `root` must exist. An empty `relative` (or ".") names the root itself. `must_exist` makes a path that
/// does not exist a `missing` problem; otherwise a path that does not exist yet (an output folder to
/// create) is resolved through its longest existing parent. Never throws for bad `relative`.
ServedPath resolve_served_path(const std::filesystem::path& root, const std::string& relative, bool must_exist = true);

/// `path` relative to `root` as a '/'-separated string (both resolved); empty when `path` is the root.
std::string served_relative(const std::filesystem::path& root, const std::filesystem::path& path);

}  // namespace forensim
