#pragma once
/// The wound timeline (Linnenbank 2015, chapter 3.2 and Figure 4.4): key positions placed at times after
/// injury (seconds), at least two, the first and last at the ends. The maps at any time are the linear
/// interpolation of the maps of the two neighbouring entries. Beyond the thesis's slider, times are real:
/// "36 hours after injury" is sample(36 * 3600).
///
/// - Hold pairs: two entries of the same key at the same local position output the same maps, so the phase
///   stays visible between them (sampling there returns the key's maps exactly).
/// - Instant cut: two entries at the same time; before it the earlier entry's maps blend, from it on the
///   later one's (the thesis's jump from scab to maturation, chapter 4.3.5).
/// - Re-rendering keys: between two entries of one key that re-renders (maturation), the key is rendered at
///   the local position interpolated between the entries' positions.
///
/// All key maps cover the canvas region; outside it every map equals the healthy skin, so sample_full() only
/// rewrites the region of a full-texture map set.

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "wound/key_position.hpp"
#include "wound/map_set.hpp"
#include "wound/tiled_map_set.hpp"
#include "wound/wound_canvas.hpp"

namespace forensim {

/// One place of a key position on the timeline.
struct TimelineEntry {
  double time_s = 0.0;                     ///< seconds after injury
  std::shared_ptr<const KeyPosition> key;  ///< the key position
  double local_position = 0.0;             ///< position within the key's phase, [0, 1] (re-rendering keys)
  std::string label;                       ///< shown in sheets ("scab", "maturation end")
};

class Timeline {
 public:
  /// Validates the entries: at least 2, each with a key, finite non-decreasing times (at most two at one
  /// time), local positions in [0, 1]. Throws InputError naming the entry otherwise.
  explicit Timeline(std::vector<TimelineEntry> entries);

  /// Renders every distinct (key, local position) once for `canvas` (kept for re-rendering keys).
  void render(std::shared_ptr<const WoundCanvas> canvas);

  const std::vector<TimelineEntry>& entries() const { return m_entries; }
  /// Tiled maps of entry i (region size). Requires render().
  const TiledMapSet& entry_tiles(std::size_t i) const;
  /// Maps of entry i as a plain map set of the region's size. Requires render().
  MapSet entry_maps(std::size_t i) const;
  /// True when entries i and j output the same maps (a hold pair: the same key at the same position).
  bool same_maps(std::size_t i, std::size_t j) const;
  /// Writes entry i's maps into the region of a full-texture set (as sample_full).
  void write_entry_full(std::size_t i, MapSet& full) const;
  /// Index of the entry pair sampled at time t: the last i with time_i <= t (i + 1 < #entries), clamped.
  std::size_t segment_at(double time_s) const;
  /// Blend weight of the segment's right entry at t (0 before the first entry, 1 after the last).
  double weight_at(double time_s) const;

  /// Maps at `time_s` into `out` (tiled, region size), copy-on-write: tiles where the two neighbouring key
  /// positions are both the skin stay the skin, tiles they share (or all of them at a key, in a hold or an
  /// instant cut) are shared, and only the others are blended, so a sample costs what its changed texels
  /// cost. Buffers `out` alone holds are reused. Times before the first entry give the first entry's maps,
  /// after the last the last one's.
  void sample(double time_s, TiledMapSet& out) const;
  /// sample() as a plain map set of the region's size (resized only when its size differs).
  void sample(double time_s, MapSet& out) const;
  /// Writes the maps at `time_s` into the region of a full-texture set `full` (texels outside the region
  /// are left as they are: the skin, from skin_map_set). Throws InputError for a set of another size.
  void sample_full(double time_s, MapSet& full) const;

  /// JSON description: entries with their times (seconds and human), labels, keys and parameters.
  nlohmann::json describe() const;
  const WoundCanvas& canvas() const { return *m_canvas; }

 private:
  std::vector<TimelineEntry> m_entries;
  std::vector<std::size_t> m_map_of_entry;  // entry -> index into m_maps
  std::vector<TiledMapSet> m_maps;
  std::shared_ptr<const WoundCanvas> m_canvas;
};

}  // namespace forensim
