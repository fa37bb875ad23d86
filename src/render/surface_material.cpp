#include "render/surface_material.hpp"

namespace forensim {

SurfaceMaterial SurfaceMaterial::skin(const Vec3f& albedo) {
  SurfaceMaterial m;
  m.model = ShadingModel::skin;
  m.base_colour = albedo;
  m.roughness = 0.45;
  m.specular = 0.45;
  m.subsurface = 0.65;
  m.cap_colour = Vec3f(0.45f, 0.10f, 0.08f);  // cut flesh: muscle red
  return m;
}

SurfaceMaterial SurfaceMaterial::bone() {
  SurfaceMaterial m;
  m.base_colour = Vec3f(0.78f, 0.72f, 0.58f);
  m.roughness = 0.7;
  m.specular = 0.3;
  m.cap_colour = Vec3f(0.85f, 0.80f, 0.66f);
  return m;
}

SurfaceMaterial SurfaceMaterial::clay() {
  SurfaceMaterial m;
  m.base_colour = Vec3f(0.60f, 0.58f, 0.55f);
  m.roughness = 0.6;
  m.specular = 0.35;
  return m;
}

SurfaceMaterial SurfaceMaterial::field(const std::string& name, double lo, double hi, ColormapName map) {
  SurfaceMaterial m;
  m.colour_source = ColourSource::scalar_field;
  m.scalar_field = name;
  m.field_min = lo;
  m.field_max = hi;
  m.colormap = Colormap(map);
  m.base_colour = Vec3f(1, 1, 1);
  m.roughness = 0.6;
  m.specular = 0.25;
  return m;
}

}  // namespace forensim
