#pragma once
/// ParaView data (.pvd) time series: one collection file listing the .vtu written at each simulated time,
/// so ParaView plays a desiccation run as an animation (File > Open the .pvd; its time is the "time" given
/// here, e.g. days).

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace forensim {

/// One time step of a series: the simulated time and the data file's path relative to the .pvd's folder.
struct PvdEntry {
  double time = 0.0;
  std::string file;
};

/// A .pvd collection that is complete on disk after every step: the constructor writes it (empty or with
/// `entries`), and add() rewrites it atomically, so an interrupted run still leaves a valid series of the
/// steps finished so far.
class PvdSeries {
 public:
  /// Starts the series at `pvd_path` with `entries` (e.g. from read_pvd, to resume a run) and writes it.
  /// Throws IoError when it cannot be written.
  explicit PvdSeries(std::filesystem::path pvd_path, std::vector<PvdEntry> entries = {});

  /// Appends a step: `time` (finite; any unit, ParaView shows it as is) and `relative_vtu_path` (relative
  /// to the .pvd's folder, '/'-separated), then rewrites the file atomically. Throws InputError for a
  /// non-finite time or an empty path, IoError when the file cannot be written.
  void add(double time, const std::string& relative_vtu_path);

  const std::vector<PvdEntry>& entries() const { return m_entries; }
  const std::filesystem::path& path() const { return m_path; }

 private:
  void write() const;

  std::filesystem::path m_path;
  std::vector<PvdEntry> m_entries;
};

/// Reads the DataSet entries (timestep, file) of a .pvd collection in file order. Throws IoError when it
/// cannot be read, InputError(path, "line N", problem) when it is not a VTK Collection or a timestep is not
/// a finite number.
std::vector<PvdEntry> read_pvd(const std::filesystem::path& path);
/// read_pvd on file contents already in memory; `source` names them in errors.
std::vector<PvdEntry> parse_pvd(std::string_view bytes, const std::string& source);

}  // namespace forensim
