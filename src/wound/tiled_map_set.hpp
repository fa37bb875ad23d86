#pragma once
/// A wound's maps (colour, reflection, height; wound/map_set.hpp) over its canvas region, stored in square
/// tiles of tiled_map_tile texels that share the healthy skin until written (copy-on-write). A tile's map
/// that equals the skin (colour = the canvas's upper skin, reflection = the set's skin reflection, height 0)
/// holds no storage; the others own their texels. Key positions write only the tiles the wound reaches, and
/// a timeline sample blends only the tiles where its two key positions differ and shares the rest (the skin,
/// or a key's own tile), so both cost what their changed texels cost, not the texture's size.
///
/// Precision: colour and reflection are 16-bit unorm (values clamped to [0, 1]; a step of 1/65535, finer
/// than the 8- and 16-bit PNG files they are written to), height is 32-bit float (written to EXR in mm).
/// Tiles are independent, so tile-parallel loops give the same maps at any thread count.

#include <cstdint>
#include <memory>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "image/image.hpp"
#include "wound/map_set.hpp"

namespace forensim {

/// Side of a map tile, texels.
inline constexpr int tiled_map_tile = 64;
/// Texels of one tile (its storage; edge tiles use the part inside the set).
inline constexpr std::size_t tiled_map_tile_texels = static_cast<std::size_t>(tiled_map_tile) * tiled_map_tile;

/// 16-bit unorm code of v (clamped to [0, 1], rounded to nearest).
inline std::uint16_t to_unorm16(float v) {
  v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
  return static_cast<std::uint16_t>(v * 65535.0f + 0.5f);
}
/// to_unorm16 of four values (an RGBA texel) at once.
inline void to_unorm16x4(const float* v, std::uint16_t* out) {
#if defined(__SSE2__)
  __m128 x = _mm_min_ps(_mm_max_ps(_mm_loadu_ps(v), _mm_setzero_ps()), _mm_set1_ps(1.0f));
  x = _mm_add_ps(_mm_mul_ps(x, _mm_set1_ps(65535.0f)), _mm_set1_ps(0.5f));
  // Truncate to int32, then to 16 bits: shifted into the signed range for the saturating pack and back.
  const __m128i i = _mm_sub_epi32(_mm_cvttps_epi32(x), _mm_set1_epi32(32768));
  const __m128i packed = _mm_xor_si128(_mm_packs_epi32(i, i), _mm_set1_epi16(static_cast<short>(0x8000)));
  _mm_storel_epi64(reinterpret_cast<__m128i*>(out), packed);
#else
  for (int k = 0; k < 4; ++k) out[k] = to_unorm16(v[k]);
#endif
}

/// Value of a 16-bit unorm code.
inline float from_unorm16(std::uint16_t q) {
  return static_cast<float>(q) * (1.0f / 65535.0f);
}

/// One tile's maps; a null map equals the skin. Texel (x, y) of the tile is at y * tiled_map_tile + x.
struct MapTile {
  std::shared_ptr<std::vector<std::uint16_t>> color;       ///< RGBA unorm16 (4 per texel) or null: upper skin
  std::shared_ptr<std::vector<std::uint16_t>> reflection;  ///< unorm16 or null: the set's skin reflection
  std::shared_ptr<std::vector<float>> height_mm;           ///< mm or null: 0
};

class TiledMapSet {
 public:
  TiledMapSet() = default;

  /// Makes this a width x height set whose tiles all equal the skin (reflection `skin_reflection`). Buffers
  /// this set alone held are kept for the next writes (no allocation when a set is rendered into again).
  void reset(int width, int height, float skin_reflection);
  /// Makes this set share every tile of `other` (no texel is copied).
  void share(const TiledMapSet& other);

  int width() const { return m_width; }
  int height() const { return m_height; }
  int tiles_x() const { return m_tiles_x; }
  int tiles_y() const { return m_tiles_y; }
  int tile_count() const { return m_tiles_x * m_tiles_y; }
  float skin_reflection() const { return m_skin_reflection; }
  /// Texels of tile t (row-major tile index) in set coordinates.
  TexelRect tile_rect(int t) const;
  const MapTile& tile(int t) const { return m_tiles[static_cast<std::size_t>(t)]; }

  /// Writable storage of tile t's colour (RGBA unorm16, tiled_map_tile_texels * 4), reflection or height,
  /// owned by this set alone (a shared one is replaced, not written through). Contents are unspecified: the
  /// caller writes every texel of tile_rect(t). Not thread-safe: take the pointers first, then fill tiles in
  /// parallel.
  std::uint16_t* own_color(int t);
  std::uint16_t* own_reflection(int t);
  float* own_height(int t);
  /// Points tile t's maps at `tile`'s (sharing them).
  void share_tile(int t, const MapTile& tile);

  /// Texels held by own (non-skin) tiles, per map: colour + reflection + height tiles times tile texels.
  std::size_t stored_texels() const;

  /// Writes the set into `out` with its texel (0, 0) at (x0, y0) of `out` (clipped), skin tiles from
  /// `upper_skin` (RGBA, this set's size) and the skin reflection. `out` must be a checked map set.
  void write_into(const Image& upper_skin, MapSet& out, int x0, int y0) const;
  /// The set as a map set of its own size.
  MapSet to_map_set(const Image& upper_skin) const;

 private:
  template <typename T>
  T* own(std::shared_ptr<std::vector<T>>& map, std::vector<std::shared_ptr<std::vector<T>>>& spare, std::size_t size);

  int m_width = 0, m_height = 0, m_tiles_x = 0, m_tiles_y = 0;
  float m_skin_reflection = 0.0f;
  std::vector<MapTile> m_tiles;
  std::vector<std::shared_ptr<std::vector<std::uint16_t>>> m_spare_color, m_spare_reflection;
  std::vector<std::shared_ptr<std::vector<float>>> m_spare_height;
};

/// out = a (1 - t) + b t (t clamped to [0, 1]), tile by tile: tiles where a and b are both skin stay skin, tiles a and
/// b share are shared, only the others are blended (in parallel). Skin colour comes from `upper_skin` (RGBA, the sets'
/// size); out's skin reflection is the blend of a's and b's. a and b must have the same size (InputError otherwise);
/// out must not be a or b.
void lerp_tiled_map_sets(const TiledMapSet& a, const TiledMapSet& b, float t, const Image& upper_skin,
                         TiledMapSet& out);

}  // namespace forensim
