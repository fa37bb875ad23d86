#pragma once
/// Simple line plots of time curves (water, mass, volume per part) drawn into an Image: axes with ticks,
/// one coloured line per series, a legend and optional reference points (e.g. the Papageorgopoulou et al.
/// 2015 measurement). Written here because the render module draws lines and text but has no plotting,
/// and a plotting library would be a new dependency for a few PNGs.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

struct CurveSeries {
  std::string name;
  std::vector<double> x, y;  ///< same length
};

struct ReferencePoint {
  double x = 0.0, y = 0.0;
  std::string label;
};

struct CurvePlotStyle {
  int width = 900, height = 560;
  std::string title, x_label, y_label;
  double y_min = 0.0, y_max = 0.0;  ///< y range; y_min == y_max: from the data
};

/// Renders the series (display-referred RGBA, sRGB). Series with fewer than two points are drawn as dots.
Image plot_curves(const std::vector<CurveSeries>& series, const CurvePlotStyle& style,
                  const std::vector<ReferencePoint>& references = {});

}  // namespace forensim
