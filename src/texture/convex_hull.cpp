#include "texture/convex_hull.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace forensim {

namespace {

bool lexicographic_less(const Vec2& a, const Vec2& b) {
  return a[0] < b[0] || (a[0] == b[0] && a[1] < b[1]);
}

// Sorted (x, then y) copy without exact duplicates; throws for non-finite points.
std::vector<Vec2> sorted_unique(const std::vector<Vec2>& points) {
  for (std::size_t i = 0; i < points.size(); ++i)
    require_input(std::isfinite(points[i][0]) && std::isfinite(points[i][1]), "convex hull",
                  "point " + std::to_string(i), "is not finite");
  std::vector<Vec2> p = points;
  std::sort(p.begin(), p.end(), lexicographic_less);
  p.erase(std::unique(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a == b; }), p.end());
  return p;
}

// Lines 5-6 / 10-11: drop the middle of the last three points while they do not make a right turn.
void append_right_turn(std::vector<Vec2>& list, const Vec2& p) {
  list.push_back(p);
  while (list.size() > 2 &&
         !(turn_determinant(list[list.size() - 3], list[list.size() - 2], list[list.size() - 1]) < 0.0))
    list.erase(list.end() - 2);
}

}  // namespace

double turn_determinant(const Vec2& p1, const Vec2& p2, const Vec2& p3) {
  return (p2[0] - p1[0]) * (p3[1] - p1[1]) - (p3[0] - p1[0]) * (p2[1] - p1[1]);
}

std::vector<Vec2> convex_hull(const std::vector<Vec2>& points) {
  const std::vector<Vec2> p = sorted_unique(points);  // line 1
  const std::size_t n = p.size();
  if (n < 3) return p;
  std::vector<Vec2> upper{p[0], p[1]};                                   // line 2
  for (std::size_t i = 2; i < n; ++i) append_right_turn(upper, p[i]);    // lines 3 to 6
  std::vector<Vec2> lower{p[n - 1], p[n - 2]};                           // line 7
  for (std::size_t i = n - 2; i-- > 0;) append_right_turn(lower, p[i]);  // lines 8 to 11: n - 2 downto 1
  lower.erase(lower.begin());                                            // line 12
  lower.pop_back();
  upper.insert(upper.end(), lower.begin(), lower.end());  // line 13
  return upper;
}

std::vector<Vec2> convex_hull_monotone_chain(const std::vector<Vec2>& points) {
  const std::vector<Vec2> p = sorted_unique(points);
  const std::size_t n = p.size();
  if (n < 3) return p;
  // Counter-clockwise (y-up) hull: lower chain left to right, then upper chain right to left.
  std::vector<Vec2> hull(2 * n);
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (k >= 2 && turn_determinant(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = n - 1, t = k + 1; i-- > 0;) {
    while (k >= t && turn_determinant(hull[k - 2], hull[k - 1], p[i]) <= 0.0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  // Same convention as convex_hull: clockwise from the smallest point.
  std::reverse(hull.begin() + 1, hull.end());
  return hull;
}

double polygon_signed_area(const std::vector<Vec2>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % polygon.size()];
    twice += a[0] * b[1] - b[0] * a[1];
  }
  return 0.5 * twice;
}

}  // namespace forensim
