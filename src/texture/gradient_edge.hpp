#pragma once
/// Gradient edges of the wound thesis (Linnenbank 2015, chapter 3.3.3): a colour gradient drawn inward or outward from
/// the border of a wound shape over a thickness, for the red glow around a wound (outward, thickness 100 at
/// the thesis's texture scale) and the darker rim of a scab (inward). Algorithm 3.4 takes, for every texel,
/// its distance to the nearest hull edge (Algorithm 3.3); draw_gradient_edge_hull does exactly that, and
/// draw_gradient_edge does the same from the shape mask alone through the exact distance transform.
/// Distances and thickness are in texels: the caller converts from mm on the skin (texels = mm *
/// texels_per_mm) so that the glow looks the same at any texture resolution.

#include <vector>

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

/// Algorithm 3.3: distance from point p to the segment l1 l2 (to the nearer end point when the projection
/// falls outside the segment, else to the line). A degenerate segment (l1 = l2) gives |p - l1|.
double point_segment_distance(const Vec2& l1, const Vec2& l2, const Vec2& p);

/// Smallest Algorithm 3.3 distance from p to the edges of the closed polygon `hull` (last vertex joins the
/// first); |p - hull[0]| for one vertex, +infinity for none.
double polygon_edge_distance(const std::vector<Vec2>& hull, const Vec2& p);

/// Which side of the shape border a gradient is drawn on (Algorithm 3.4's renderSide).
enum class GradientSide { inside, outside };

/// Per-texel distance (texels) used by the mask form of Algorithm 3.4: for texels on `side` of the shape
/// (channel 0 >= threshold is inside), the distance from the texel centre to the nearest texel centre on the
/// other side, computed by the exact distance transform (equal to the brute-force minimum); +infinity on the
/// other side and where the other side is empty. Single-channel data image.
Image edge_distance(const Image& shape, GradientSide side, float threshold = 0.5f);

/// Algorithm 3.4 from the mask: texels on the other side of `side` are black (0, 0, 0, 1); texels with
/// distance d (edge_distance) <= thickness get Lerp(color_from, color_to, d / thickness); farther texels
/// are black. RGBA linear image of the shape's size. thickness in texels, > 0 (InputError otherwise).
Image draw_gradient_edge(const Image& shape, double thickness, GradientSide side, const Vec4f& color_from,
                         const Vec4f& color_to, float threshold = 0.5f);

/// Algorithm 3.4 exactly as the thesis computes it: the distance of each texel centre (x + 0.5, y + 0.5) to
/// the nearest edge of `hull` (texel coordinates, closed polygon) by Algorithm 3.3, the side from `shape`.
/// O(texels x hull edges), rows in parallel. Same output convention as draw_gradient_edge.
Image draw_gradient_edge_hull(const std::vector<Vec2>& hull, const Image& shape, double thickness, GradientSide side,
                              const Vec4f& color_from, const Vec4f& color_to, float threshold = 0.5f);

}  // namespace forensim
