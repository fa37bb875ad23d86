#include "core/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <sstream>
#include <system_error>

#include "core/error.hpp"

namespace forensim {
namespace {
std::atomic<unsigned> g_counter{0};
}

void check_output_path(const std::filesystem::path& path, OutputKind kind) {
  namespace fs = std::filesystem;
  if (path.empty()) throw IoError("(empty)", "an output path is empty");
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status)) {
    if (kind == OutputKind::file && fs::is_directory(status)) throw IoError(path.string(), "is a folder, not a file");
    if (kind == OutputKind::folder && !fs::is_directory(status)) {
      throw IoError(path.string(), "cannot create output folder: a file of that name exists");
    }
  }
  // The nearest existing ancestor (the path itself for an existing folder) must be a writable folder.
  fs::path existing = fs::absolute(path, ec);
  if (ec) throw IoError(path.string(), "cannot resolve the output path: " + ec.message());
  if (kind == OutputKind::file || !fs::is_directory(status)) existing = existing.parent_path();
  while (existing.has_relative_path() && !fs::exists(existing, ec)) existing = existing.parent_path();
  if (!fs::is_directory(existing, ec)) {
    throw IoError(path.string(), "cannot create the output: " + existing.string() + " is not a folder");
  }
  if (::access(existing.c_str(), W_OK | X_OK) != 0) {
    throw IoError(path.string(), "cannot create the output: the folder " + existing.string() + " is not writable");
  }
}

AtomicFile::AtomicFile(std::filesystem::path final_path, bool binary) : m_final(std::move(final_path)) {
  std::error_code ec;
  if (m_final.has_parent_path()) std::filesystem::create_directories(m_final.parent_path(), ec);
  if (ec) throw IoError(m_final.parent_path().string(), "cannot create folder: " + ec.message());
  // Keep the final extension last: some writers (Assimp, OpenEXR) choose the format from it.
  m_temporary = m_final.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" +
                                         std::to_string(g_counter.fetch_add(1)) + "-" + m_final.filename().string());
  m_stream.open(m_temporary,
                binary ? std::ios::binary | std::ios::out | std::ios::trunc : std::ios::out | std::ios::trunc);
  if (!m_stream) throw IoError(m_final.string(), "cannot open for writing");
}

AtomicFile::~AtomicFile() {
  if (m_committed) return;
  if (m_stream.is_open()) m_stream.close();
  std::error_code ec;
  std::filesystem::remove(m_temporary, ec);
}

void AtomicFile::release_stream() {
  if (m_stream.is_open()) {
    m_stream.flush();
    if (!m_stream) throw IoError(m_final.string(), "write failed");
    m_stream.close();
  }
}

void AtomicFile::commit() {
  if (m_committed) return;
  release_stream();
  std::error_code ec;
  std::filesystem::rename(m_temporary, m_final, ec);
  if (ec) throw IoError(m_final.string(), "cannot move the finished file into place: " + ec.message());
  m_committed = true;
}

void write_file_atomic(const std::filesystem::path& path, std::string_view bytes) {
  AtomicFile file(path);
  file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

std::string read_file(const std::filesystem::path& path, std::size_t max_bytes) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path.string(), "is a folder, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), "cannot open for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw IoError(path.string(), "cannot determine file size");
  if (static_cast<std::size_t>(size) > max_bytes) {
    throw IoError(path.string(), "file is larger than the limit of " + std::to_string(max_bytes) + " bytes");
  }
  in.seekg(0, std::ios::beg);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), size);
  if (!in) throw IoError(path.string(), "read failed");
  return bytes;
}

}  // namespace forensim
