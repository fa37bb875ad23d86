#include "texture/polygon_fill.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "texture/convex_hull.hpp"

namespace forensim {

namespace {

struct Edge {
  Vec2 a, b;
};

struct Crossing {
  double x;
  int direction;  // +1 when the edge goes down the image (y increasing), -1 up
};

// Crossings of the horizontal line y = yc with the edges, half-open in y, sorted by x.
void scanline_crossings(const std::vector<Edge>& edges, double yc, std::vector<Crossing>& out) {
  out.clear();
  for (const Edge& e : edges) {
    const double y0 = e.a[1], y1 = e.b[1];
    if (y0 == y1) continue;
    const bool down = y0 < y1;
    const double lo = down ? y0 : y1, hi = down ? y1 : y0;
    if (!(yc >= lo && yc < hi)) continue;
    const double x = e.a[0] + (yc - y0) * (e.b[0] - e.a[0]) / (y1 - y0);
    out.push_back({x, down ? 1 : -1});
  }
  std::sort(out.begin(), out.end(), [](const Crossing& p, const Crossing& q) { return p.x < q.x; });
}

// Calls span(x_begin, x_end) for every inside interval [x_begin, x_end) of the sorted crossings.
template <typename F>
void for_each_span(const std::vector<Crossing>& crossings, FillRule rule, const F& span) {
  int winding = 0;
  for (std::size_t i = 0; i + 1 < crossings.size(); ++i) {
    winding += rule == FillRule::even_odd ? 1 : crossings[i].direction;
    const bool inside = rule == FillRule::even_odd ? (winding % 2 != 0) : (winding != 0);
    if (inside && crossings[i + 1].x > crossings[i].x) span(crossings[i].x, crossings[i + 1].x);
  }
}

}  // namespace

void fill_hull(Image& target, const std::vector<Vec2>& hull, float inside_value, float outside_value) {
  if (hull.size() < 3 || target.empty()) return;
  for (std::size_t i = 0; i < hull.size(); ++i)
    if (!std::isfinite(hull[i][0]) || !std::isfinite(hull[i][1]))
      throw InputError("hull", "vertex " + std::to_string(i), "is not finite");
  // GetHullBoundingBox: texels whose centres lie in the box.
  double x_min = hull[0][0], x_max = x_min, y_min = hull[0][1], y_max = y_min;
  for (const Vec2& p : hull) {
    x_min = std::min(x_min, p[0]);
    x_max = std::max(x_max, p[0]);
    y_min = std::min(y_min, p[1]);
    y_max = std::max(y_max, p[1]);
  }
  const auto first = [](double lo, int size) {
    return static_cast<int>(std::clamp(std::ceil(lo - 0.5), 0.0, static_cast<double>(size)));
  };
  const auto last = [](double hi, int size) {
    return static_cast<int>(std::clamp(std::floor(hi - 0.5), -1.0, static_cast<double>(size - 1)));
  };
  const int x0 = first(x_min, target.width()), x1 = last(x_max, target.width());
  const int y0 = first(y_min, target.height()), y1 = last(y_max, target.height());
  if (x0 > x1 || y0 > y1) return;
  const double orientation = polygon_signed_area(hull) >= 0.0 ? 1.0 : -1.0;
  parallel_for(
      static_cast<std::size_t>(y0), static_cast<std::size_t>(y1) + 1,
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        for (int x = x0; x <= x1; ++x) {
          const Vec2 centre(x + 0.5, y + 0.5);
          bool in_hull = true;  // line 2
          for (std::size_t i = 0; i < hull.size(); ++i) {
            // IsOnRightSide (eq. 4.4), mirrored for a clockwise hull.
            if (orientation * turn_determinant(hull[i], hull[(i + 1) % hull.size()], centre) < 0.0) {
              in_hull = false;
              break;
            }
          }
          target.at(x, y, 0) = in_hull ? inside_value : outside_value;
        }
      },
      4);
}

Image fill_polygon(int width, int height, const std::vector<std::vector<Vec2>>& rings, FillRule rule, bool antialias,
                   int subsamples) {
  require_input(subsamples >= 1 && subsamples <= 256, "fill_polygon", "subsamples", "must be in 1..256");
  Image out(width, height, 1, 0.0f, PixelEncoding::data);
  std::vector<Edge> edges;
  for (std::size_t r = 0; r < rings.size(); ++r) {
    const std::vector<Vec2>& ring = rings[r];
    for (std::size_t i = 0; i < ring.size(); ++i) {
      // Bounded so that edge slopes stay finite (a NaN crossing would break the scanline sort).
      require_input(std::abs(ring[i][0]) <= 1e9 && std::abs(ring[i][1]) <= 1e9, "polygon",
                    "ring " + std::to_string(r) + " vertex " + std::to_string(i),
                    "is not finite or lies beyond 1e9 texels");
      if (ring.size() >= 2) edges.push_back({ring[i], ring[(i + 1) % ring.size()]});
    }
  }
  if (out.empty() || edges.empty()) return out;
  const int lines = antialias ? subsamples : 1;
  parallel_for(
      0, static_cast<std::size_t>(height),
      [&](std::size_t row) {
        const int y = static_cast<int>(row);
        std::vector<Crossing> crossings;
        float* values = out.pixel(0, y);
        const float weight = 1.0f / static_cast<float>(lines);
        for (int s = 0; s < lines; ++s) {
          const double yc = antialias ? y + (s + 0.5) / lines : y + 0.5;
          scanline_crossings(edges, yc, crossings);
          for_each_span(crossings, rule, [&](double xa, double xb) {
            if (!antialias) {
              // Texels whose centres lie in [xa, xb).
              const double lo = std::clamp(std::ceil(xa - 0.5), 0.0, static_cast<double>(width));
              const double hi = std::clamp(std::ceil(xb - 0.5), 0.0, static_cast<double>(width));
              for (int x = static_cast<int>(lo); x < static_cast<int>(hi); ++x) values[x] = 1.0f;
              return;
            }
            const double a = std::clamp(xa, 0.0, static_cast<double>(width));
            const double b = std::clamp(xb, 0.0, static_cast<double>(width));
            if (!(b > a)) return;
            const int first = static_cast<int>(std::floor(a));
            const int last = std::min(width - 1, static_cast<int>(std::ceil(b)) - 1);
            for (int x = first; x <= last; ++x) {
              const double overlap = std::min(b, x + 1.0) - std::max(a, static_cast<double>(x));
              if (overlap > 0.0) values[x] += weight * static_cast<float>(overlap);
            }
          });
        }
        if (antialias)
          for (int x = 0; x < width; ++x) values[x] = std::min(values[x], 1.0f);
      },
      4);
  return out;
}

}  // namespace forensim
