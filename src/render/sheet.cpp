#include "render/sheet.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "render/renderer.hpp"
#include "render/text.hpp"

namespace forensim {

Image make_sheet(const std::vector<SheetCell>& cells, int columns, const std::string& title, const SheetStyle& style) {
  require_input(columns >= 1, "sheet", "columns", "must be at least 1");
  require_input(!cells.empty(), "sheet", "cells", "no pictures to lay out");
  int cell_w = 1, cell_h = 1;
  bool any_caption = false;
  for (const SheetCell& cell : cells) {
    cell_w = std::max(cell_w, cell.image.width());
    cell_h = std::max(cell_h, cell.image.height());
    any_caption = any_caption || !cell.caption.empty();
  }
  const int count = static_cast<int>(cells.size());
  columns = std::min(columns, count);
  const int rows = (count + columns - 1) / columns;
  const auto font_size = [](double px) { return std::isfinite(px) ? std::clamp(px, 1.0, 500.0) : 16.0; };
  const double caption_px = font_size(style.caption_px), title_px = font_size(style.title_px);
  const int pad = std::clamp(style.padding, 0, 10000);
  const int caption_h = any_caption ? static_cast<int>(std::ceil(caption_px * 1.5)) : 0;
  const int title_h = title.empty() ? 0 : static_cast<int>(std::ceil(title_px * 1.6));
  const long long width = static_cast<long long>(columns) * (cell_w + pad) + pad;
  const long long height = static_cast<long long>(rows) * (cell_h + caption_h + pad) + pad + title_h;
  require_input(width * height <= static_cast<long long>(max_image_pixels), "sheet", "", "sheet would be too large");
  Image sheet(static_cast<int>(width), static_cast<int>(height), 4, 0.0f, PixelEncoding::srgb);
  sheet.fill(style.background);
  if (!title.empty()) draw_text(sheet, 0.5 * width, pad * 0.75, title, title_px, style.text, TextAlign::centre);
  for (int i = 0; i < count; ++i) {
    const int col = i % columns, row = i / columns;
    const int x0 = pad + col * (cell_w + pad);
    const int y0 = title_h + pad + row * (cell_h + caption_h + pad);
    const Image& picture = cells[static_cast<std::size_t>(i)].image;
    sheet.paste(picture, x0 + (cell_w - picture.width()) / 2, y0 + (cell_h - picture.height()) / 2, true);
    const std::string& caption = cells[static_cast<std::size_t>(i)].caption;
    if (!caption.empty())
      draw_text(sheet, x0 + 0.5 * cell_w, y0 + cell_h + 0.25 * caption_px, caption, caption_px, style.text,
                TextAlign::centre);
  }
  return sheet;
}

std::vector<Image> render_turntable(const Scene& scene, const RenderSettings& settings,
                                    const std::vector<ViewName>& views, const FramingOptions& framing) {
  const Renderer renderer(scene);
  const BoundingBox box = scene.visible_bounds();
  const double aspect = static_cast<double>(settings.width) / std::max(1, settings.height);
  std::vector<Image> frames;
  for (ViewName view : views) frames.push_back(renderer.render(frame_view(box, view, aspect, framing), settings));
  return frames;
}

std::vector<Image> render_turntable(const Scene& scene, const RenderSettings& settings, int frames,
                                    double elevation_deg, const FramingOptions& framing) {
  require_input(frames >= 1 && frames <= 3600, "turntable", "frames", "must be in 1..3600");
  const Renderer renderer(scene);
  const BoundingBox box = scene.visible_bounds();
  const double aspect = static_cast<double>(settings.width) / std::max(1, settings.height);
  // Frame every view with the same distance (the widest need) so the subject does not pulse in size.
  double distance = 0;
  std::vector<Camera> cameras;
  for (int i = 0; i < frames; ++i) {
    cameras.push_back(orbit_view(box, 360.0 * i / frames, elevation_deg, aspect, framing));
    distance = std::max(distance, (cameras.back().eye() - cameras.back().target()).norm());
  }
  std::vector<Image> out;
  for (const Camera& c : cameras) {
    const Vec3 eye = c.target() - c.forward() * distance;
    const Camera fixed = c.projection() == ProjectionKind::orthographic
                             ? Camera::orthographic(eye, c.target(), c.up(), c.view_height())
                             : Camera::look_at(eye, c.target(), c.up(), c.vertical_fov_deg());
    out.push_back(renderer.render(fixed, settings));
  }
  return out;
}

}  // namespace forensim
