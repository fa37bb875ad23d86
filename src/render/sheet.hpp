#pragma once
/// Contact sheets: pictures in a grid with a caption under each and a title on top (timelines of
/// states, before/after comparisons, turntables), and turntable rendering.

#include <string>
#include <vector>

#include "core/types.hpp"
#include "image/image.hpp"
#include "render/camera.hpp"
#include "render/render_settings.hpp"
#include "render/scene.hpp"

namespace forensim {

struct SheetCell {
  Image image;          ///< display-referred picture (any size; centred in its cell)
  std::string caption;  ///< e.g. "day 3"
};

struct SheetStyle {
  Vec4f background = Vec4f(1, 1, 1, 1);           ///< display (sRGB) colour
  Vec4f text = Vec4f(0.08f, 0.08f, 0.08f, 1.0f);  ///< display (sRGB) colour
  int padding = 16;                               ///< pixels around and between cells
  double caption_px = 18.0;
  double title_px = 26.0;
};

/// Grid of `columns` cells (rows as needed) under `title`; every cell is as large as the largest
/// picture, with its caption centred below. Throws InputError if `columns` < 1 or there are no cells.
Image make_sheet(const std::vector<SheetCell>& cells, int columns, const std::string& title,
                 const SheetStyle& style = {});

/// Renders the scene from each named view (framed around what the cut planes leave); the Embree scene
/// is built once.
std::vector<Image> render_turntable(const Scene& scene, const RenderSettings& settings,
                                    const std::vector<ViewName>& views, const FramingOptions& framing = {});
/// Renders `frames` views evenly spaced around the subject at `elevation_deg`, starting from the front.
std::vector<Image> render_turntable(const Scene& scene, const RenderSettings& settings, int frames,
                                    double elevation_deg = 10.0, const FramingOptions& framing = {});

}  // namespace forensim
