#pragma once
/// Convex hull of 2D points, for the wound outline the user draws on the skin (Linnenbank 2015, chapter
/// 4.2.1): Algorithm 4.1 (De Berg et al., upper and lower hulls with the right-turn test of eq. 4.4), and
/// Andrew's monotone chain as an independent reference. Both return the hull's vertices without collinear or
/// duplicate points, in clockwise order in a y-up frame (negative signed area), starting at the
/// lexicographically smallest point (smallest x, then smallest y). In texel coordinates (y down) that order
/// looks counter-clockwise on screen. Non-finite points are rejected (InputError).

#include <vector>

#include "core/types.hpp"

namespace forensim {

/// Eq. 4.4: det | p2 - p1, p3 - p1 | = (p2.x - p1.x)(p3.y - p1.y) - (p3.x - p1.x)(p2.y - p1.y); p3 lies to the
/// right of p1 -> p2 (a right turn, y-up) when det < 0, on the line when det = 0.
double turn_determinant(const Vec2& p1, const Vec2& p2, const Vec2& p3);

/// Algorithm 4.1 (sorting by x, ties by y; exact duplicates merged first). One point gives one vertex,
/// two distinct points or a collinear set the two extreme points, an empty set an empty hull.
std::vector<Vec2> convex_hull(const std::vector<Vec2>& points);

/// Andrew's monotone chain (1979), returned in the same convention as convex_hull.
std::vector<Vec2> convex_hull_monotone_chain(const std::vector<Vec2>& points);

/// Signed area of a closed polygon (shoelace), positive when counter-clockwise in a y-up frame.
double polygon_signed_area(const std::vector<Vec2>& polygon);

}  // namespace forensim
