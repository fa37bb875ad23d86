#pragma once
/// How a rendered surface looks: where its base colour comes from (constant, vertex colours, a texture
/// through the mesh's corner UVs, or a scalar field through a colormap), how it reflects light (a plain
/// diffuse + GGX specular surface, or skin with a subsurface-scattering approximation), and its opacity.

#include <memory>
#include <string>

#include "core/types.hpp"
#include "image/colormap.hpp"
#include "image/image.hpp"

namespace forensim {

enum class ColourSource {
  constant,        ///< SurfaceMaterial::base_colour
  vertex_colours,  ///< TriMesh::colors (linear RGBA), times base_colour
  texture,         ///< base_texture sampled at the corner UVs, times base_colour
  scalar_field,    ///< a per-vertex scalar field mapped through a colormap over [field_min, field_max]
};

enum class ShadingModel {
  standard,  ///< Lambertian diffuse + GGX specular
  skin,      ///< wrap-lighting subsurface approximation with red-shifted, softened terminator + GGX specular
};

struct SurfaceMaterial {
  ColourSource colour_source = ColourSource::constant;
  ShadingModel model = ShadingModel::standard;
  Vec3f base_colour = Vec3f(0.72f, 0.72f, 0.72f);  ///< linear albedo (multiplier for other sources)
  std::shared_ptr<const Image> base_texture;       ///< linear colour texture (read_png decodes sRGB)
  std::shared_ptr<const Image> normal_map;         ///< tangent-space normal map, values in [0,1] (data)
  std::string scalar_field;                        ///< name in TriMesh::vertex_fields.scalars
  Colormap colormap{ColormapName::viridis};
  double field_min = 0.0, field_max = 1.0;  ///< scalar range mapped to the colormap's ends

  double roughness = 0.55;  ///< GGX roughness (perceptual, squared for alpha), [0.02, 1]
  double specular = 0.5;    ///< specular level; Fresnel reflectance at normal incidence F0 = 0.08 * specular
  /// Skin: fraction of diffuse light that scatters under the surface [0,1] and how far it wraps past
  /// the terminator per channel (red travels furthest, Jimenez et al. 2010 / Penner 2011 style).
  double subsurface = 0.6;
  Vec3f scatter_wrap = Vec3f(0.65f, 0.30f, 0.22f);
  /// Skin: distance (scene units, mm) the scattered light travels under the surface, used to soften
  /// shadow edges cast onto the skin.
  double scatter_distance_mm = 2.0;

  double opacity = 1.0;          ///< < 1: semi-transparent overlay; only the faces towards the viewer are drawn
  bool double_sided = true;      ///< shade back faces (open scans) instead of leaving them black
  double crease_angle_deg = 30;  ///< corners whose vertex normal is further than this from the face are flat
  /// Cut-away cross-section: colour of the cap drawn where the cut plane passes through the (closed)
  /// object; negative components mean "base colour darkened".
  Vec3f cap_colour = Vec3f(-1, -1, -1);
  bool draw_cap = true;  ///< draw the cap; if false the cut object is seen hollow
  /// Wireframe overlay: triangle edges drawn in wire_colour out to this distance (mm, on the surface) on
  /// each side; 0 = none. Shows the element structure, e.g. the tet faces on a cut through a tet mesh.
  double wire_width_mm = 0.0;
  Vec3f wire_colour = Vec3f(0.06f, 0.05f, 0.05f);  ///< linear

  /// Skin with the given linear albedo.
  static SurfaceMaterial skin(const Vec3f& albedo = Vec3f(0.56f, 0.34f, 0.25f));
  /// Dry bone: pale, rough, a little yellow.
  static SurfaceMaterial bone();
  /// Neutral clay for quick looks.
  static SurfaceMaterial clay();
  /// Scalar field `field` over [lo, hi] through `map`.
  static SurfaceMaterial field(const std::string& field, double lo, double hi,
                               ColormapName map = ColormapName::viridis);
};

}  // namespace forensim
