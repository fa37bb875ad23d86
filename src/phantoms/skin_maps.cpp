#include "phantoms/skin_maps.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/timer.hpp"
#include "geometry/mesh_measures.hpp"
#include "image/png_io.hpp"
#include "phantoms/arm_phantom.hpp"
#include "texture/solid_noise.hpp"
#include "texture/uv_bake.hpp"

namespace forensim {

struct SkinTexture::Noise {
  explicit Noise(std::uint64_t seed)
      : tone(seed ^ 0x746f6e65ULL),
        lines(seed ^ 0x6c696e6573ULL),
        veins(seed ^ 0x7665696e73ULL),
        perfusion(seed ^ 0x70657266ULL),
        pores(seed ^ 0x706f726573ULL, 0.8),
        freckles(seed ^ 0x667265636bULL, 0.8) {}
  GradientNoise3 tone, lines, veins, perfusion;
  WorleyNoise3 pores, freckles;
};

namespace {

// Feature sizes (mm).
constexpr double pore_cell_mm = 0.7;  // one pore per cell at most
constexpr double pore_radius = 0.22;  // of the cell
constexpr double pore_depth_mm = 0.035;
constexpr double line_mm = 1.3;  // skin lines (fine relief)
constexpr double line_depth_mm = 0.012;
constexpr double freckle_cell_mm = 4.0;
constexpr double crease_mm = 1.1;  // spacing of knuckle creases
constexpr double crease_depth_mm = 0.03;

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// 1 for features of at least three texels, fading to 0 at 1.5 texels (band limit of the bake).
double fade(double feature_mm, double texel_mm) {
  return smoothstep(1.5, 3.0, feature_mm / texel_mm);
}

/// Base reflectance of skin without melanin and melanin's absorption spectrum (per unit melanin), linear RGB:
/// melanin absorbs blue most (Donner et al. 2008 use a similar two-chromophore split).
const Vec3 base_albedo(0.95, 0.80, 0.70);
const Vec3 melanin_absorption(0.35, 0.75, 1.30);

}  // namespace

SkinTexture::SkinTexture(std::uint64_t seed, double texel_mm)
    : m_seed(seed), m_texel_mm(texel_mm), m_noise(std::make_shared<const Noise>(seed)) {
  require_input(std::isfinite(texel_mm) && texel_mm > 0.0, "skin texture", "texel_mm",
                "must be positive, got " + std::to_string(texel_mm));
  const ArmPhantom arm;
  for (const ArmPhantom::Digit& digit : arm.digits()) {
    for (std::size_t j = 0; j < 3; ++j) {
      if (j > 0 && digit.joints[j] == digit.joints[j - 1]) continue;
      const Vec3 axis = (digit.joints[j + 1] - digit.joints[j]).normalized();
      m_knuckles.push_back(digit.joints[j] + Vec3(0, 0, 0.85 * digit.radii[j]));
      m_knuckle_axes.push_back(axis);
      m_knuckle_radii.push_back(digit.radii[j]);
    }
  }
}

double SkinTexture::height_mm(const Vec3& p, const Vec3& n) const {
  const Noise& noise = *m_noise;
  double h = 0.0;
  const double pore_fade = fade(2.0 * pore_radius * pore_cell_mm, m_texel_mm);
  if (pore_fade > 0.0) {
    const CellularSample c = noise.pores.evaluate(p / pore_cell_mm);
    if (noise.pores.cell_value(c.cell) < 0.75)
      h -= pore_fade * pore_depth_mm * (1.0 - smoothstep(0.0, pore_radius, c.f1));
  }
  const double line_fade = fade(line_mm, m_texel_mm);
  if (line_fade > 0.0) {
    // Ridged noise: thin grooves between flat plateaus, like the skin's line pattern.
    const double r = std::abs(noise.lines.evaluate(p / line_mm));
    h -= line_fade * line_depth_mm * (1.0 - smoothstep(0.0, 0.15, r));
  }
  const double crease_fade = fade(crease_mm, m_texel_mm);
  if (crease_fade > 0.0 && n.z() > 0.0) {
    for (std::size_t k = 0; k < m_knuckles.size(); ++k) {
      const double d2 = (p - m_knuckles[k]).squaredNorm();
      const double sigma = 0.6 * m_knuckle_radii[k];
      if (d2 > 9.0 * sigma * sigma) continue;
      const double w = std::exp(-d2 / (2.0 * sigma * sigma)) * n.z();
      const double phase = (p - m_knuckles[k]).dot(m_knuckle_axes[k]) / crease_mm + 0.3 * noise.lines.evaluate(p / 3.0);
      h -= crease_fade * crease_depth_mm * w * std::pow(0.5 + 0.5 * std::cos(2.0 * 3.14159265358979 * phase), 4.0);
    }
  }
  return h;
}

SkinSample SkinTexture::evaluate(const Vec3& p, const Vec3& n) const {
  const Noise& noise = *m_noise;
  SkinSample s;
  const double dorsal = smoothstep(-0.2, 0.5, n.z());
  // Melanin: more on the back of hand and forearm than on the palm, low-frequency variation, knuckles, freckles.
  double melanin = 0.2 + 0.25 * dorsal;
  melanin += 0.08 * noise.tone.fractal(p / 30.0, 3) +
             0.04 * fade(6.0, m_texel_mm) * noise.tone.evaluate(p / 6.0 + Vec3(17, 3, 5));
  for (std::size_t k = 0; k < m_knuckles.size(); ++k) {
    const double sigma = 0.7 * m_knuckle_radii[k];
    const double d2 = (p - m_knuckles[k]).squaredNorm();
    if (d2 < 9.0 * sigma * sigma) melanin += 0.15 * dorsal * std::exp(-d2 / (2.0 * sigma * sigma));
  }
  {
    const CellularSample c = noise.freckles.evaluate(p / freckle_cell_mm);
    const double density = 0.04 + 0.30 * dorsal;
    if (noise.freckles.cell_value(c.cell) < density) {
      const double radius_mm = 0.35 + 0.65 * noise.freckles.cell_value(c.cell, 1);
      const double f1_mm = c.f1 * freckle_cell_mm;
      melanin += 0.45 * fade(2.0 * radius_mm, m_texel_mm) * (1.0 - smoothstep(0.55 * radius_mm, radius_mm, f1_mm));
    }
  }
  melanin = std::max(melanin, 0.02);
  s.melanin = melanin;
  const double h = height_mm(p, n);
  const double pore = std::clamp(-h / pore_depth_mm, 0.0, 1.0);  // ~1 in pores and deep creases
  for (int c = 0; c < 3; ++c) s.epidermis[c] = base_albedo[c] * std::exp(-melanin * melanin_absorption[c]);
  s.epidermis *= 1.0 - 0.12 * pore;
  // Dermis: blood red, redder and more even on the palm, perfusion variation, faint bluish veins on the back.
  const Vec3 dermis_palm(0.70, 0.20, 0.16), dermis_back(0.62, 0.19, 0.15);
  s.dermis = dermis_palm + dorsal * (dermis_back - dermis_palm);
  s.dermis *= 1.0 + 0.10 * noise.perfusion.fractal(p / 12.0, 3);
  // Vein lines are the zero set of a noise field; their width (in noise units) grows to at least two texels so
  // they stay band-limited, with the strength scaled down to keep their average contribution.
  const double vein_width = std::max(0.035, 2.0 * m_texel_mm / 22.0);
  const double vein = (1.0 - smoothstep(0.0, vein_width, std::abs(noise.veins.fractal(p / 22.0, 2)))) * dorsal;
  s.dermis += 0.35 * (0.035 / vein_width) * vein * (Vec3(0.28, 0.16, 0.26) - s.dermis);
  // Specular: smooth dorsal skin shines more than the palm; pores and creases less.
  s.specular = std::clamp((0.28 + 0.14 * dorsal) * (1.0 - 0.6 * pore) * (1.0 + 0.1 * noise.perfusion.evaluate(p / 5.0)),
                          0.0, 1.0);
  s.height_mm = h;
  return s;
}

Vec3 SkinTexture::tangent_normal(const Vec3& p, const Vec3& n, const Vec3& tangent, const Vec3& bitangent) const {
  const double step = 0.25 * m_texel_mm;
  const double dh_dt = (height_mm(p + step * tangent, n) - height_mm(p - step * tangent, n)) / (2.0 * step);
  const double dh_db = (height_mm(p + step * bitangent, n) - height_mm(p - step * bitangent, n)) / (2.0 * step);
  return Vec3(-dh_dt, -dh_db, 1.0).normalized();
}

SkinMaps make_skin_maps(const TriMesh& mesh, int resolution, std::uint64_t seed) {
  require_input(resolution >= 16 && resolution <= 8192, "skin maps", "resolution",
                "must be in [16, 8192], got " + std::to_string(resolution));
  require_input(mesh.has_uvs(), "skin maps", "mesh", "has no UVs");
  Stopwatch watch;
  SkinMaps maps;
  maps.resolution = resolution;
  maps.seed = seed;
  double area = 0.0, uv_area = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& f = mesh.triangles[t];
    const Tri& u = mesh.triangle_uvs[t];
    area +=
        triangle_area(mesh.positions[static_cast<std::size_t>(f[0])], mesh.positions[static_cast<std::size_t>(f[1])],
                      mesh.positions[static_cast<std::size_t>(f[2])]);
    const Vec2 a = mesh.uvs[static_cast<std::size_t>(u[1])] - mesh.uvs[static_cast<std::size_t>(u[0])];
    const Vec2 b = mesh.uvs[static_cast<std::size_t>(u[2])] - mesh.uvs[static_cast<std::size_t>(u[0])];
    uv_area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
  }
  require_input(area > 0.0 && uv_area > 0.0, "skin maps", "mesh", "has no surface or UV area");
  maps.texel_mm = std::sqrt(area / uv_area) / resolution;
  const SkinTexture skin(seed, maps.texel_mm);
  const UvRaster raster = rasterize_uv(mesh, resolution, resolution, 2);  // exact values 2 texels past borders
  maps.epidermis = Image(resolution, resolution, 3, 0.0f, PixelEncoding::linear);
  maps.dermis = Image(resolution, resolution, 3, 0.0f, PixelEncoding::linear);
  maps.specular = Image(resolution, resolution, 1, 0.0f, PixelEncoding::data);
  maps.normal = Image(resolution, resolution, 3, 0.0f, PixelEncoding::data);
  // Background beyond the dilated rings: a flat normal and typical tones, so coarse mip levels stay plausible.
  maps.epidermis.fill(Vec4f(0.75f, 0.55f, 0.42f, 1.0f));
  maps.dermis.fill(Vec4f(0.66f, 0.19f, 0.15f, 1.0f));
  maps.specular.fill(0.3f);
  maps.normal.fill(Vec4f(0.5f, 0.5f, 1.0f, 1.0f));
  parallel_for(
      0, raster.texels.size(),
      [&](std::size_t i) {
        const UvTexel& t = raster.texels[i];
        const SkinSample s = skin.evaluate(t.position, t.normal);
        const Vec3 nt = skin.tangent_normal(t.position, t.normal, t.tangent, t.bitangent);
        for (int c = 0; c < 3; ++c) {
          maps.epidermis.at(t.x, t.y, c) = static_cast<float>(s.epidermis[c]);
          maps.dermis.at(t.x, t.y, c) = static_cast<float>(s.dermis[c]);
          maps.normal.at(t.x, t.y, c) = static_cast<float>(0.5 * nt[c] + 0.5);
        }
        maps.specular.at(t.x, t.y) = static_cast<float>(s.specular);
      },
      512);
  const std::vector<std::uint8_t> covered = coverage(raster);
  const int rings = 2 + resolution / 512;
  for (Image* image : {&maps.epidermis, &maps.dermis, &maps.specular, &maps.normal}) {
    dilate_gutter(*image, covered, rings);
  }
  maps.seconds = watch.seconds();
  return maps;
}

void write_skin_maps(const SkinMaps& maps, const std::filesystem::path& folder) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw IoError(folder.string(), "cannot create folder: " + ec.message());
  write_png(folder / "epidermis.png", maps.epidermis);  // linear -> sRGB-encoded
  write_png(folder / "dermis.png", maps.dermis);
  PngWriteOptions data;
  data.transfer = PngTransfer::identity;
  write_png(folder / "specular.png", maps.specular, data);
  write_png(folder / "normal.png", maps.normal, data);
}

std::vector<Vec4f> sample_map_at_vertices(const TriMesh& mesh, const Image& map) {
  require_input(mesh.has_uvs(), "mesh", "", "has no UVs");
  std::vector<Vec4f> colors(mesh.positions.size(), Vec4f(0, 0, 0, 1));
  std::vector<bool> done(mesh.positions.size(), false);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(mesh.triangles[t][k]);
      if (done[v]) continue;
      done[v] = true;
      colors[v] = map.sample_uv(mesh.uvs[static_cast<std::size_t>(mesh.triangle_uvs[t][k])], WrapMode::clamp);
      colors[v].w() = 1.0f;
    }
  }
  return colors;
}

}  // namespace forensim
