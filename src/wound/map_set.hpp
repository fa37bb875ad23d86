#pragma once
/// The maps one key position of a wound timeline outputs (Linnenbank 2015, chapter 3.2 and 4.3): colour,
/// reflection and height, plus the normal map derived from height. Sets are blended linearly between key
/// positions, so the blend is the hot loop of a timeline: it runs over rows in parallel on floats, with no
/// allocation, and may be limited to the rectangle where a wound's maps differ from the skin.

#include <filesystem>
#include <string>

#include "image/image.hpp"

namespace forensim {

/// Half-open texel rectangle [x0, x1) x [y0, y1).
struct TexelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

/// The maps of one key position, all of the same size.
struct MapSet {
  Image color;       ///< RGBA, linear colour (the wound painted over the skin)
  Image reflection;  ///< 1 channel data in [0, 1]: the thesis's reflection (whiter = more specular)
  Image height_mm;   ///< 1 channel data: displacement along the surface normal, mm (scab thickness)

  int width() const { return color.width(); }
  int height() const { return color.height(); }
};

/// A set of width x height maps: colour `color`, reflection `reflection`, height 0.
MapSet make_map_set(int width, int height, const Vec4f& color = Vec4f(0, 0, 0, 1), float reflection = 0.0f);

/// Makes `set` width x height maps for rendering into: reuses its buffers when it already has that size
/// (no allocation), fills reflection with `reflection` and height with 0; the colour is left as it was (the
/// caller writes every texel).
void prepare_map_set(MapSet& set, int width, int height, float reflection);

/// Throws InputError unless the three maps of `set` have the same size and the expected channel counts
/// (4, 1, 1). `what` names the set in the message.
void check_map_set(const MapSet& set, const std::string& what);

/// out = a (1 - t) + b t on every map, inside `rect` only (clipped to the maps). a, b and out must already
/// have the same size and channels (InputError otherwise); out may alias a or b. No allocation; rows in
/// parallel; results do not depend on the thread count.
void lerp_map_sets(const MapSet& a, const MapSet& b, float t, MapSet& out, const TexelRect& rect);

/// lerp_map_sets over the whole maps.
void lerp_map_sets(const MapSet& a, const MapSet& b, float t, MapSet& out);

/// Copies `part` (maps of rect's size) into `full` with its top-left texel at (rect.x0, rect.y0), clipped.
void paste_map_set(MapSet& full, const MapSet& part, const TexelRect& rect);

/// Roughness for PBR shading from the thesis's reflection value: lerp(max, min, reflection), so a
/// reflective texel is smooth. 1 channel data image.
Image roughness_from_reflection(const Image& reflection, float min_roughness = 0.25f, float max_roughness = 0.7f);

/// Writes a set into `folder` as <prefix>_color.png (sRGB), <prefix>_reflection.png,
/// <prefix>_roughness.png, <prefix>_height.exr (mm, 32-bit float), <prefix>_height.png (0..max_height_mm
/// as 0..1) and <prefix>_normal.png (from height at `texels_per_mm`). Atomic writes; IoError on failure.
/// Returns the names of the files written (relative to folder).
std::vector<std::string> write_map_set(const MapSet& set, const std::filesystem::path& folder,
                                       const std::string& prefix, double texels_per_mm, double max_height_mm = 1.0);

}  // namespace forensim
