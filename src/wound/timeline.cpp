#include "wound/timeline.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "wound/duration.hpp"

namespace forensim {

Timeline::Timeline(std::vector<TimelineEntry> entries) : m_entries(std::move(entries)) {
  if (m_entries.size() < 2) {
    throw InputError("wound timeline", "entries", "needs at least two key positions (one at each end)");
  }
  for (std::size_t i = 0; i < m_entries.size(); ++i) {
    const auto& e = m_entries[i];
    const std::string where = "entry " + std::to_string(i);
    if (!e.key) throw InputError("wound timeline", where, "has no key position");
    if (!std::isfinite(e.time_s) || e.time_s < 0.0) throw InputError("wound timeline", where, "time must be >= 0");
    if (!(e.local_position >= 0.0 && e.local_position <= 1.0)) {
      throw InputError("wound timeline", where, "local position must be in [0, 1]");
    }
    if (i > 0 && e.time_s < m_entries[i - 1].time_s) {
      throw InputError("wound timeline", where, "times must not decrease");
    }
    if (i > 1 && e.time_s == m_entries[i - 2].time_s) {
      throw InputError("wound timeline", where, "at most two entries (an instant cut) may share a time");
    }
  }
}

void Timeline::render(std::shared_ptr<const WoundCanvas> canvas) {
  m_canvas = std::move(canvas);
  m_maps.clear();
  m_map_of_entry.assign(m_entries.size(), 0);
  std::vector<std::size_t> first_of_map;
  for (std::size_t i = 0; i < m_entries.size(); ++i) {
    const auto& e = m_entries[i];
    bool found = false;
    for (std::size_t m = 0; m < first_of_map.size() && !found; ++m) {
      const auto& f = m_entries[first_of_map[m]];
      if (f.key == e.key && f.local_position == e.local_position) {
        m_map_of_entry[i] = m;
        found = true;
      }
    }
    if (found) continue;
    m_map_of_entry[i] = m_maps.size();
    first_of_map.push_back(i);
    m_maps.emplace_back();
    e.key->render_into(*m_canvas, e.local_position, m_maps.back());
  }
}

const TiledMapSet& Timeline::entry_tiles(std::size_t i) const {
  if (m_maps.empty()) throw Error("wound timeline: render() was not called");
  return m_maps.at(m_map_of_entry.at(i));
}

MapSet Timeline::entry_maps(std::size_t i) const {
  return entry_tiles(i).to_map_set(m_canvas->upper_skin);
}

bool Timeline::same_maps(std::size_t i, std::size_t j) const {
  return &entry_tiles(i) == &entry_tiles(j);
}

void Timeline::write_entry_full(std::size_t i, MapSet& full) const {
  const TiledMapSet& maps = entry_tiles(i);
  const WoundCanvas& c = *m_canvas;
  if (full.width() != c.full_width || full.height() != c.full_height) {
    throw InputError("wound timeline", "write_entry_full", "the full map set differs from the texture size");
  }
  maps.write_into(c.upper_skin, full, c.region.x0, c.region.y0);
}

std::size_t Timeline::segment_at(double t) const {
  std::size_t i = 0;
  while (i + 2 < m_entries.size() && m_entries[i + 1].time_s <= t) ++i;
  return i;
}

double Timeline::weight_at(double t) const {
  const std::size_t i = segment_at(t);
  const double t0 = m_entries[i].time_s, t1 = m_entries[i + 1].time_s;
  if (t <= t0) return 0.0;
  if (t >= t1) return 1.0;
  return (t - t0) / (t1 - t0);
}

void Timeline::sample(double t, TiledMapSet& out) const {
  if (m_maps.empty()) throw Error("wound timeline: render() was not called");
  const std::size_t i = segment_at(t);
  const double w = weight_at(t);
  const auto& a = m_entries[i];
  const auto& b = m_entries[i + 1];
  const TiledMapSet& ma = entry_tiles(i);
  const TiledMapSet& mb = entry_tiles(i + 1);
  if (a.key == b.key && a.key->rerenders() && a.local_position != b.local_position && w > 0.0 && w < 1.0) {
    a.key->render_into(*m_canvas, a.local_position + (b.local_position - a.local_position) * w, out);
    return;
  }
  if (&ma == &mb || w <= 0.0 || w >= 1.0) {
    out.share(w >= 1.0 ? mb : ma);
    return;
  }
  lerp_tiled_map_sets(ma, mb, static_cast<float>(w), m_canvas->upper_skin, out);
}

void Timeline::sample(double t, MapSet& out) const {
  TiledMapSet tiles;
  sample(t, tiles);
  if (out.width() != tiles.width() || out.height() != tiles.height() || out.color.channels() != 4 ||
      out.reflection.channels() != 1 || out.height_mm.channels() != 1 || out.reflection.width() != tiles.width() ||
      out.height_mm.width() != tiles.width()) {
    out = make_map_set(tiles.width(), tiles.height());
  }
  tiles.write_into(m_canvas->upper_skin, out, 0, 0);
}

void Timeline::sample_full(double t, MapSet& full) const {
  if (m_maps.empty()) throw Error("wound timeline: render() was not called");
  const WoundCanvas& c = *m_canvas;
  if (full.width() != c.full_width || full.height() != c.full_height) {
    throw InputError("wound timeline", "sample_full", "the full map set differs from the texture size");
  }
  TiledMapSet tiles;
  sample(t, tiles);
  tiles.write_into(c.upper_skin, full, c.region.x0, c.region.y0);
}

nlohmann::json Timeline::describe() const {
  nlohmann::json j;
  j["entries"] = nlohmann::json::array();
  for (std::size_t i = 0; i < m_entries.size(); ++i) {
    const auto& e = m_entries[i];
    nlohmann::json x;
    x["time_s"] = e.time_s;
    x["time"] = format_injury_time(e.time_s);
    x["phase"] = e.key->name();
    x["label"] = e.label;
    x["local_position"] = e.local_position;
    x["rerenders"] = e.key->rerenders();
    x["parameters"] = e.key->describe();
    if (i > 0) {
      const auto& p = m_entries[i - 1];
      x["holds_previous"] = p.key == e.key && p.local_position == e.local_position;
      x["instant_cut"] = p.time_s == e.time_s;
    }
    j["entries"].push_back(x);
  }
  if (m_canvas) {
    j["region"] = {m_canvas->region.x0, m_canvas->region.y0, m_canvas->region.x1, m_canvas->region.y1};
    j["texture_size"] = {m_canvas->full_width, m_canvas->full_height};
    j["texels_per_mm"] = m_canvas->texels_per_mm;
    j["closing_distance_mm"] = m_canvas->closing_distance_mm;
    j["wound_texels"] = m_canvas->wound_texels;
    j["distance"] = m_canvas->distance == DistanceMode::surface ? "surface" : "uv";
  }
  return j;
}

}  // namespace forensim
