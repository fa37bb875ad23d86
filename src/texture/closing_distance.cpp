#include "texture/closing_distance.hpp"

#include <algorithm>

#include "texture/convex_hull.hpp"

namespace forensim {

double closing_distance(const std::vector<Vec2>& hull) {
  double max_dist = 0.0;                                          // line 1
  for (std::size_t e = 0; e < hull.size(); ++e)                   // line 2
    for (std::size_t f = e + 1; f < hull.size(); ++f)             // line 3 (pairs once: the distance is symmetric)
      max_dist = std::max(max_dist, (hull[f] - hull[e]).norm());  // lines 4 and 5
  return max_dist;
}

double closing_distance_of_points(const std::vector<Vec2>& points) {
  return closing_distance(convex_hull(points));
}

}  // namespace forensim
