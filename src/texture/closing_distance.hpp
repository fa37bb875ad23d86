#pragma once
/// Closing distance of a wound (Linnenbank 2015, chapter 4.3.5, Algorithm 4.3): the largest distance
/// between two vertices of the wound's convex hull, i.e. the hull's diameter (the thesis's "vector from edge
/// e to edge f" runs between hull vertices). The maturation phase shrinks the wound over half of it
/// (eq. 4.8). Units are those of the points (texels or mm on the skin).

#include <vector>

#include "core/types.hpp"

namespace forensim {

/// Algorithm 4.3: max |h_i - h_j| over all pairs of hull vertices (O(h^2)); 0 for fewer than two vertices.
double closing_distance(const std::vector<Vec2>& hull);

/// Closing distance of any point set: closing_distance(convex_hull(points)), equal to the set's diameter.
double closing_distance_of_points(const std::vector<Vec2>& points);

}  // namespace forensim
