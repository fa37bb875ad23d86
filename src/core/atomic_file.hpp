#pragma once
/// Files written atomically: data goes to a temporary name in the same folder and is renamed onto the
/// final name only when complete, so an error or interruption never leaves a half-written output.

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace forensim {

/// An output file under construction. Write through stream() or path(), then commit(); if the object is
/// destroyed without commit() the temporary file is removed.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path final_path, bool binary = true);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Stream open on the temporary file.
  std::ofstream& stream() { return m_stream; }
  /// The temporary path, for libraries that write files themselves (close the stream first: see release_stream).
  const std::filesystem::path& temporary_path() const { return m_temporary; }
  /// Closes the stream so another writer can use temporary_path().
  void release_stream();
  /// Flushes, checks for write errors and renames onto the final path. Throws IoError on failure.
  void commit();
  const std::filesystem::path& final_path() const { return m_final; }

 private:
  std::filesystem::path m_final, m_temporary;
  std::ofstream m_stream;
  bool m_committed = false;
};

/// What an output path names: a file (written through AtomicFile) or a folder (created with its parents).
enum class OutputKind { file, folder };

/// Checks, before any work and without creating anything, that an output can be made at `path`: a file
/// output must not name an existing folder, a folder output must not name an existing non-folder, and the
/// nearest existing ancestor must be a folder this process may write into. Commands call it for each output
/// option first, so a bad output path fails in milliseconds rather than after the computation. Throws IoError
/// naming `path` and the problem.
void check_output_path(const std::filesystem::path& path, OutputKind kind);

/// Writes `bytes` to `path` atomically. Throws IoError.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);
/// Reads a whole file; throws IoError when it cannot be read or is larger than `max_bytes`.
std::string read_file(const std::filesystem::path& path, std::size_t max_bytes = std::size_t{4} << 30);

}  // namespace forensim
