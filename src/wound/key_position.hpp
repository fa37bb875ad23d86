#pragma once
/// A key position of a wound timeline (Linnenbank 2015, chapter 3.2): a small value class that renders the
/// maps of one moment of healing from the wound's canvas. Key positions are built from a job file
/// (wound/wound_job.hpp); each phase of a wound type is one class.

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "wound/map_set.hpp"
#include "wound/tiled_map_set.hpp"
#include "wound/wound_canvas.hpp"

namespace forensim {

class KeyPosition {
 public:
  virtual ~KeyPosition() = default;
  /// Phase name ("scab"), as written in job files.
  virtual std::string name() const = 0;
  /// Renders the maps of this key position over canvas.region into `out` (a tiled set of the region's size):
  /// only the tiles the wound's maps reach are written, the others share the skin; buffers `out` already
  /// holds are reused, as a GPU reuses its render targets. `local_position` in [0, 1] is the position inside
  /// the phase; only keys that re-render use it (the thesis's maturation, chapter 4.3.5). Deterministic for
  /// the canvas's seed at any thread count.
  virtual void render_into(const WoundCanvas& canvas, double local_position, TiledMapSet& out) const = 0;
  /// The maps as a plain map set of the region's size.
  MapSet render(const WoundCanvas& canvas, double local_position) const {
    TiledMapSet out;
    render_into(canvas, local_position, out);
    return out.to_map_set(canvas.upper_skin);
  }
  /// True when the key re-renders at every position between two of its entries instead of being blended.
  virtual bool rerenders() const { return false; }
  /// The key's parameters, for the timeline's JSON description.
  virtual nlohmann::json describe() const { return nlohmann::json::object(); }
};

}  // namespace forensim
