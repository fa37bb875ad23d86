#pragma once
/// Procedural skin maps for the forearm-uv phantom (or any skin mesh with UVs in mm): the two-layer skin of
/// the desiccation paper's shading (Frerichs et al., section 8.3; Donner et al.): an epidermis colour (its
/// reflectance with melanin: base tone, melanin variation, freckles, pores, darker knuckles and back of the
/// hand), a dermis colour (redder, with faint veins), a specular weight and a tangent-space normal map of the
/// pore and skin-line relief. Everything is evaluated from SOLID noise at the 3D point each texel shows, so
/// the maps agree across UV seams.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "core/types.hpp"
#include "geometry/tri_mesh.hpp"
#include "image/image.hpp"

namespace forensim {

/// Skin at one surface point.
struct SkinSample {
  Vec3 epidermis = Vec3::Zero();  ///< linear RGB reflectance of the upper layer
  Vec3 dermis = Vec3::Zero();     ///< linear RGB colour of the lower layer
  double specular = 0.0;          ///< specular weight in [0, 1]
  double height_mm = 0.0;         ///< relief (pores negative, skin lines), mm
  double melanin = 0.0;           ///< melanin amount (dimensionless, about 0.1 to 1)
};

/// The procedural skin as a function of the surface point: a small value class (pbrt-style texture).
/// `texel_mm` band-limits it: features smaller than about two texels fade out, so baked maps do not alias.
class SkinTexture {
 public:
  SkinTexture(std::uint64_t seed, double texel_mm);
  /// Skin at point `p` (mm, arm phantom frame: z dorsal) with unit surface normal `n`.
  SkinSample evaluate(const Vec3& p, const Vec3& n) const;
  /// The relief alone (cheaper than evaluate()), mm.
  double height_mm(const Vec3& p, const Vec3& n) const;
  /// Tangent-space normal (x along `tangent`, y along `bitangent`, z along `n`) of the relief, from its
  /// surface gradient by central differences in the tangent plane.
  Vec3 tangent_normal(const Vec3& p, const Vec3& n, const Vec3& tangent, const Vec3& bitangent) const;
  double texel_mm() const { return m_texel_mm; }
  std::uint64_t seed() const { return m_seed; }

 private:
  struct Noise;  // the seeded noise fields (texture module, a private dependency)
  std::uint64_t m_seed;
  double m_texel_mm;
  std::shared_ptr<const Noise> m_noise;
  std::vector<Vec3> m_knuckles;  ///< dorsal points over the digit joints (ArmPhantom)
  std::vector<Vec3> m_knuckle_axes;
  std::vector<double> m_knuckle_radii;
};

/// The four maps, resolution x resolution, rows top to bottom, v up (forensim::Image conventions).
struct SkinMaps {
  Image epidermis;  ///< RGB, linear colour (written sRGB-encoded): upper skin colour
  Image dermis;     ///< RGB, linear colour (written sRGB-encoded): lower skin colour
  Image specular;   ///< one channel, data (written as is): specular weight
  Image normal;     ///< RGB, data: tangent-space normal n * 0.5 + 0.5, OpenGL convention (+Y = +v, up)
  int resolution = 0;
  std::uint64_t seed = 0;
  double texel_mm = 0.0;  ///< mean surface size of a texel
  double seconds = 0.0;   ///< time to bake
};

/// Bakes the skin maps of `mesh_with_uvs` (mm, arm phantom frame; vertex normals used when present) at
/// resolution x resolution texels with noise seeded by `seed`, dilating into the gutter. Deterministic for a
/// seed (at any thread count). Throws InputError without UVs or for a resolution outside [16, 8192].
SkinMaps make_skin_maps(const TriMesh& mesh_with_uvs, int resolution = 2048, std::uint64_t seed = 1);

/// Writes epidermis.png, dermis.png (8-bit sRGB), specular.png and normal.png (8-bit, linear values) into
/// `folder` (created if missing), atomically. Throws IoError.
void write_skin_maps(const SkinMaps& maps, const std::filesystem::path& folder);

/// Vertex colours sampled from a map at each vertex's UV (the first corner that uses the vertex), for
/// pictures with renderers that take vertex colours. #V RGBA, linear.
std::vector<Vec4f> sample_map_at_vertices(const TriMesh& mesh_with_uvs, const Image& map);

}  // namespace forensim
