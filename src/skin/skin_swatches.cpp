#include "skin/skin_swatches.hpp"

#include "core/error.hpp"
#include "image/color.hpp"

namespace forensim {

std::vector<SkinStage> default_skin_stages(const SkinShader& shader, double livor_oxygen) {
  const double dried = 240.0;
  return {{"fresh", 1.0, 1.0, 0.0},
          {"livor", 1.0, livor_oxygen, 0.0},
          {"m=0.75", 0.75, livor_oxygen, dried},
          {"m=0.50", 0.5, livor_oxygen, dried},
          {"green", green_stage_moisture(shader), livor_oxygen, dried},
          {"m=0.15", 0.15, livor_oxygen, dried},
          {"dried", 0.0, livor_oxygen, dried}};
}

Image make_skin_swatch(const SkinShader& shader, const SkinLayers& layers, const SkinStage& stage, int width,
                       int height) {
  require_input(width >= 2 && width <= 4096 && height >= 2 && height <= 4096, "skin swatch", "size",
                "must be in [2, 4096]");
  require_input(layers.size() >= 1, "skin swatch", "layers", "need at least one vertex");
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y) {
    const double s = static_cast<double>(y) / (height - 1);
    const Vec3 c =
        shader.shade_vertex(layers.vertex_epidermis[0], layers.vertex_absorption_hydrated[0],
                            layers.vertex_absorption_dehydrated[0], s, 1.0, stage.oxygen, stage.moisture, stage.hours);
    for (int x = 0; x < width; ++x)
      image.set_rgba(x, y, Vec4f(static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]), 1.0f));
  }
  return to_srgb(image);
}

}  // namespace forensim
