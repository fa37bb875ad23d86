#pragma once
/// Colour maps for scalar fields (moisture, tissue depth, errors): perceptually uniform sequential maps
/// (viridis, inferno, magma), turbo for high-contrast, and a diverging blue-white-red for signed values.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "image/image.hpp"

namespace forensim {

enum class ColormapName { viridis, inferno, magma, turbo, blue_white_red, grey };

class Colormap {
 public:
  explicit Colormap(ColormapName name = ColormapName::viridis) : m_name(name) {}
  /// Colormap by name ("viridis", "inferno", "magma", "turbo", "blue_white_red", "grey"); throws
  /// InputError naming `source` for an unknown name.
  static Colormap from_name(const std::string& name, const std::string& source = "colormap");

  ColormapName name() const { return m_name; }
  /// Display (sRGB-encoded) colour at t in [0,1] (clamped; NaN gives the t = 0 colour).
  /// viridis/inferno/magma: 6th-degree polynomial fits of the matplotlib maps (Matt Zucker, 2017, max error
  /// about 0.01); turbo: Google's polynomial approximation (Mikhailov 2019); blue_white_red: Moreland's
  /// "cool to warm" diverging map (2009) through its control points.
  Vec3f sample_srgb(double t) const;
  /// Linear-light colour at t, for shading surfaces in the renderer.
  Vec3f sample(double t) const;
  /// Linear colour of `value` mapped from [lo, hi] to [0,1].
  Vec3f map(double value, double lo, double hi) const;

 private:
  ColormapName m_name;
};

/// False-colour picture of channel 0 of `values` (moisture or height maps): each pixel mapped from
/// [lo, hi] through `map`; an RGB image tagged PixelEncoding::srgb, ready for write_png or a sheet.
/// NaN values become `nan_colour` (display sRGB).
Image colorize(const Image& values, const Colormap& map, double lo, double hi,
               const Vec3f& nan_colour = Vec3f(0.5f, 0.5f, 0.5f));

/// Names of all colormaps, in ColormapName order.
std::vector<std::string> colormap_names();
/// The name of a colormap.
std::string to_string(ColormapName name);

}  // namespace forensim
