#pragma once
/// A CPU path tracer on Embree for pictures of results (not real time): one bounce of direct light from
/// every light with soft shadows, environment light with ambient occlusion, GGX specular, a skin model
/// with a subsurface approximation, semi-transparent overlays, cut-away planes with capped cross-sections,
/// then a filmic tone curve and 3D line/point overlays. Pixels use their own seeded random streams, so
/// the picture is identical at any thread count.

#include <memory>

#include "image/image.hpp"
#include "render/camera.hpp"
#include "render/render_settings.hpp"
#include "render/scene.hpp"

namespace forensim {

/// Renders a scene many times (turntables, timelines): the ray-tracing acceleration structure is built
/// once in the constructor.
class Renderer {
 public:
  /// Validates the scene (meshes, fields, textures) and builds the Embree scene. The Scene description is
  /// copied but its meshes and textures are shared, not copied; later edits of `scene` do not affect
  /// this renderer. Throws InputError for invalid objects (naming the object).
  explicit Renderer(const Scene& scene);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Display-referred picture (RGBA, sRGB-encoded, tagged PixelEncoding::srgb) from `camera`, with the
  /// scene's overlays drawn.
  Image render(const Camera& camera, const RenderSettings& settings) const;
  /// Same from the scene's camera.
  Image render(const RenderSettings& settings) const;
  /// Scene-linear RGBA (premultiplied colour, alpha = coverage) before tone mapping and overlays, for EXR.
  Image render_linear(const Camera& camera, const RenderSettings& settings) const;

  /// Per-pixel camera depth (distance along the view axis) of the first opaque surface through each pixel
  /// centre; +infinity where nothing is hit. 1 channel, tagged data.
  Image depth(const Camera& camera, int width, int height) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// One-call render of `scene` from its camera.
Image render(const Scene& scene, const RenderSettings& settings);

}  // namespace forensim
