#pragma once
/// Filling polygons into shape textures: the wound thesis's hull fill (Linnenbank 2015, chapter 4.2.2, Algorithm 4.2:
/// every texel in the hull's bounding box tested against every edge with eq. 4.4), and a general scanline
/// fill of polygons with several rings (holes, self-intersections) under the even-odd or non-zero rule,
/// optionally anti-aliased. Polygons are in continuous texel coordinates (texel (x, y) covers [x, x + 1) x
/// [y, y + 1), centre (x + 0.5, y + 0.5)); a texel is inside when its centre is.

#include <vector>

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

/// Algorithm 4.2: sets channel 0 of every texel of `target` whose centre lies in the bounding box of
/// `hull` (clipped to the image) to `inside_value` when the centre is on no edge's outer side, else to
/// `outside_value`; texels outside the box are left as they are. The outer side is the right (eq. 4.4,
/// det < 0) for a counter-clockwise hull and the left for a clockwise one (the thesis gets the
/// counter-clockwise order by flipping v from UV to texels), so either order of a convex hull works; texels
/// on an edge are inside. Fewer than 3 vertices fill nothing.
void fill_hull(Image& target, const std::vector<Vec2>& hull, float inside_value = 1.0f, float outside_value = 0.0f);

/// Point-in-polygon rule for overlapping or nested rings.
enum class FillRule { even_odd, non_zero };

/// Scanline fill: a width x height single-channel data image, 1 where the texel centre is inside the
/// polygon given by `rings` (each a closed ring, last vertex joins the first) under `rule`, else 0. With
/// `antialias` the value is instead the fraction of the texel covered (exact along x, `subsamples` sample
/// lines per texel along y, 1..256). Crossings on a scanline use half-open rules, so a centre is inside
/// exactly when a ray from it towards +x crosses the rings an odd number of times (even-odd) or with a
/// non-zero signed count (non-zero). Rows in parallel. Throws InputError for vertices that are not finite or
/// beyond 1e9 texels, and for bad sizes.
Image fill_polygon(int width, int height, const std::vector<std::vector<Vec2>>& rings,
                   FillRule rule = FillRule::non_zero, bool antialias = false, int subsamples = 16);

}  // namespace forensim
