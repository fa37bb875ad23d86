#include "server/served_path.hpp"

#include <system_error>

namespace forensim {
namespace fs = std::filesystem;

namespace {

ServedPath refuse(ServedPathProblem problem, const std::string& relative, const std::string& why) {
  ServedPath out;
  out.problem = problem;
  out.message = "path '" + relative + "' " + why;
  return out;
}

// True when `inner` equals `outer` or lies under it (both lexically normal, absolute).
bool inside(const fs::path& outer, const fs::path& inner) {
  auto o = outer.begin(), i = inner.begin();
  for (; o != outer.end(); ++o, ++i) {
    if (i == inner.end() || *o != *i) return false;
  }
  return true;
}

}  // namespace

ServedPath resolve_served_path(const fs::path& root, const std::string& relative, bool must_exist) {
  if (relative.size() > 4096)
    return refuse(ServedPathProblem::malformed, relative.substr(0, 64) + "...", "is too long");
  if (relative.find('\0') != std::string::npos) return refuse(ServedPathProblem::malformed, "", "contains a NUL byte");
  if (relative.find('\\') != std::string::npos) {
    return refuse(ServedPathProblem::malformed, relative, "contains a backslash");
  }
  if (!relative.empty() && relative.front() == '/') {
    return refuse(ServedPathProblem::malformed, relative, "is absolute; paths are relative to the served folder");
  }
  // Component by component: no "..", no empty components other than a trailing slash.
  fs::path rel;
  std::size_t start = 0;
  while (start <= relative.size()) {
    const std::size_t end = std::min(relative.find('/', start), relative.size());
    const std::string part = relative.substr(start, end - start);
    if (part == "..") return refuse(ServedPathProblem::malformed, relative, "leaves the served folder ('..')");
    if (!part.empty() && part != ".") rel /= part;
    start = end + 1;
  }
  std::error_code ec;
  const fs::path real_root = fs::canonical(root, ec);
  if (ec) return refuse(ServedPathProblem::missing, root.string(), "(the served folder) does not exist");
  const fs::path joined = real_root / rel;
  fs::path resolved;
  if (fs::exists(fs::symlink_status(joined, ec))) {
    resolved = fs::canonical(joined, ec);
    if (ec) return refuse(ServedPathProblem::outside, relative, "cannot be resolved (a broken link)");
  } else {
    if (must_exist) return refuse(ServedPathProblem::missing, relative, "does not exist");
    resolved = fs::weakly_canonical(joined, ec);
    if (ec) return refuse(ServedPathProblem::malformed, relative, "cannot be resolved");
  }
  if (!inside(real_root, resolved)) {
    return refuse(ServedPathProblem::outside, relative, "resolves outside the served folder");
  }
  ServedPath out;
  out.path = resolved;
  return out;
}

std::string served_relative(const fs::path& root, const fs::path& path) {
  std::error_code ec;
  const fs::path r = fs::weakly_canonical(root, ec);
  const fs::path p = fs::weakly_canonical(path, ec);
  const fs::path rel = p.lexically_relative(r);
  if (rel.empty() || rel == ".") return "";
  return rel.generic_string();
}

}  // namespace forensim
