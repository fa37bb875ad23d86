#include "wound/tiled_map_set.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {

namespace {

template <typename T>
void release(std::shared_ptr<std::vector<T>>& map, std::vector<std::shared_ptr<std::vector<T>>>& spare) {
  if (map && map.use_count() == 1) spare.push_back(std::move(map));
  map.reset();
}

}  // namespace

void TiledMapSet::reset(int width, int height, float skin_reflection) {
  if (width < 0 || height < 0) throw InputError("tiled map set", "size", "must not be negative");
  for (auto& tile : m_tiles) {
    release(tile.color, m_spare_color);
    release(tile.reflection, m_spare_reflection);
    release(tile.height_mm, m_spare_height);
  }
  m_width = width;
  m_height = height;
  m_tiles_x = (width + tiled_map_tile - 1) / tiled_map_tile;
  m_tiles_y = (height + tiled_map_tile - 1) / tiled_map_tile;
  m_skin_reflection = skin_reflection;
  m_tiles.assign(static_cast<std::size_t>(m_tiles_x) * static_cast<std::size_t>(m_tiles_y), MapTile{});
}

void TiledMapSet::share(const TiledMapSet& other) {
  if (&other == this) return;
  reset(other.m_width, other.m_height, other.m_skin_reflection);
  m_tiles = other.m_tiles;
}

TexelRect TiledMapSet::tile_rect(int t) const {
  const int tx = t % m_tiles_x, ty = t / m_tiles_x;
  const int x0 = tx * tiled_map_tile, y0 = ty * tiled_map_tile;
  return {x0, y0, std::min(x0 + tiled_map_tile, m_width), std::min(y0 + tiled_map_tile, m_height)};
}

template <typename T>
T* TiledMapSet::own(std::shared_ptr<std::vector<T>>& map, std::vector<std::shared_ptr<std::vector<T>>>& spare,
                    std::size_t size) {
  if (!map || map.use_count() > 1) {
    if (!spare.empty()) {
      map = std::move(spare.back());
      spare.pop_back();
    } else {
      map = std::make_shared<std::vector<T>>(size);
    }
  }
  return map->data();
}

std::uint16_t* TiledMapSet::own_color(int t) {
  return own(m_tiles[static_cast<std::size_t>(t)].color, m_spare_color, 4 * tiled_map_tile_texels);
}

std::uint16_t* TiledMapSet::own_reflection(int t) {
  return own(m_tiles[static_cast<std::size_t>(t)].reflection, m_spare_reflection, tiled_map_tile_texels);
}

float* TiledMapSet::own_height(int t) {
  return own(m_tiles[static_cast<std::size_t>(t)].height_mm, m_spare_height, tiled_map_tile_texels);
}

void TiledMapSet::share_tile(int t, const MapTile& tile) {
  MapTile& m = m_tiles[static_cast<std::size_t>(t)];
  release(m.color, m_spare_color);
  release(m.reflection, m_spare_reflection);
  release(m.height_mm, m_spare_height);
  m = tile;
}

std::size_t TiledMapSet::stored_texels() const {
  std::size_t n = 0;
  for (const auto& tile : m_tiles)
    n += (tile.color ? 1u : 0u) + (tile.reflection ? 1u : 0u) + (tile.height_mm ? 1u : 0u);
  return n * tiled_map_tile_texels;
}

void TiledMapSet::write_into(const Image& upper_skin, MapSet& out, int ox, int oy) const {
  check_map_set(out, "tiled map set output");
  if (upper_skin.width() != m_width || upper_skin.height() != m_height || upper_skin.channels() != 4) {
    throw InputError("tiled map set", "upper skin", "must be RGBA of the set's size");
  }
  parallel_for(
      0, m_tiles.size(),
      [&](std::size_t t) {
        const TexelRect r = tile_rect(static_cast<int>(t));
        const MapTile& tile = m_tiles[t];
        const int x0 = std::max(r.x0, -ox), x1 = std::min(r.x1, out.width() - ox);
        if (x1 <= x0) return;
        const std::size_t n = static_cast<std::size_t>(x1 - x0);
        for (int y = r.y0; y < r.y1; ++y) {
          if (y + oy < 0 || y + oy >= out.height()) continue;
          const std::size_t local =
              static_cast<std::size_t>(y - r.y0) * tiled_map_tile + static_cast<std::size_t>(x0 - r.x0);
          float* oc = out.color.pixel(x0 + ox, y + oy);
          if (tile.color) {
            const std::uint16_t* c = tile.color->data() + 4 * local;
            for (std::size_t k = 0; k < 4 * n; ++k) oc[k] = from_unorm16(c[k]);
          } else {
            std::copy_n(upper_skin.pixel(x0, y), 4 * n, oc);
          }
          float* orf = out.reflection.pixel(x0 + ox, y + oy);
          if (tile.reflection) {
            const std::uint16_t* c = tile.reflection->data() + local;
            for (std::size_t k = 0; k < n; ++k) orf[k] = from_unorm16(c[k]);
          } else {
            std::fill_n(orf, n, m_skin_reflection);
          }
          float* oh = out.height_mm.pixel(x0 + ox, y + oy);
          if (tile.height_mm) {
            std::copy_n(tile.height_mm->data() + local, n, oh);
          } else {
            std::fill_n(oh, n, 0.0f);
          }
        }
      },
      1);
}

MapSet TiledMapSet::to_map_set(const Image& upper_skin) const {
  MapSet out = make_map_set(m_width, m_height);
  write_into(upper_skin, out, 0, 0);
  return out;
}

namespace {

// One map of a tile to blend: a's and b's storage (null: skin) into out.
struct BlendJob {
  int tile;
  int map;  // 0 colour, 1 reflection, 2 height
  const void* a;
  const void* b;
  void* out;
};

}  // namespace

void lerp_tiled_map_sets(const TiledMapSet& a, const TiledMapSet& b, float t, const Image& upper_skin,
                         TiledMapSet& out) {
  if (a.width() != b.width() || a.height() != b.height()) {
    throw InputError("lerp_tiled_map_sets", "maps", "the sets differ in size");
  }
  if (upper_skin.width() != a.width() || upper_skin.height() != a.height() || upper_skin.channels() != 4) {
    throw InputError("lerp_tiled_map_sets", "upper skin", "must be RGBA of the sets' size");
  }
  if (&out == &a || &out == &b) throw InputError("lerp_tiled_map_sets", "out", "must not be one of the inputs");
  t = std::clamp(t, 0.0f, 1.0f);
  const float s = 1.0f - t;
  const float ra = a.skin_reflection(), rb = b.skin_reflection();
  out.reset(a.width(), a.height(), ra == rb ? ra : ra * s + rb * t);
  // Decide per tile and map (serially: storage is taken here), then blend in parallel.
  std::vector<BlendJob> jobs;
  for (int i = 0; i < a.tile_count(); ++i) {
    const MapTile& ta = a.tile(i);
    const MapTile& tb = b.tile(i);
    MapTile shared;
    if (ta.color == tb.color) shared.color = ta.color;
    if (ta.reflection == tb.reflection && (ta.reflection || ra == rb)) shared.reflection = ta.reflection;
    if (ta.height_mm == tb.height_mm) shared.height_mm = ta.height_mm;
    out.share_tile(i, shared);
    if (ta.color != tb.color) jobs.push_back({i, 0, ta.color.get(), tb.color.get(), out.own_color(i)});
    if (ta.reflection != tb.reflection || (!ta.reflection && ra != rb)) {
      jobs.push_back({i, 1, ta.reflection.get(), tb.reflection.get(), out.own_reflection(i)});
    }
    if (ta.height_mm != tb.height_mm) jobs.push_back({i, 2, ta.height_mm.get(), tb.height_mm.get(), out.own_height(i)});
  }
  parallel_for(
      0, jobs.size(),
      [&](std::size_t j) {
        const BlendJob& job = jobs[j];
        const TexelRect r = out.tile_rect(job.tile);
        const std::size_t n = static_cast<std::size_t>(r.width());
        for (int y = r.y0; y < r.y1; ++y) {
          const std::size_t local = static_cast<std::size_t>(y - r.y0) * tiled_map_tile;
          if (job.map == 0) {
            // In 16-bit code units: round(a (1 - t) + b t), a and b codes (the skin's value times 65535).
            const auto* pa = static_cast<const std::vector<std::uint16_t>*>(job.a);
            const auto* pb = static_cast<const std::vector<std::uint16_t>*>(job.b);
            std::uint16_t* o = static_cast<std::uint16_t*>(job.out) + 4 * local;
            const float* skin = upper_skin.pixel(r.x0, y);
            float va[4 * tiled_map_tile], vb[4 * tiled_map_tile];
            if (pa) {
              const std::uint16_t* q = pa->data() + 4 * local;
              for (std::size_t k = 0; k < 4 * n; ++k) va[k] = static_cast<float>(q[k]);
            } else {
              for (std::size_t k = 0; k < 4 * n; ++k) va[k] = std::clamp(skin[k], 0.0f, 1.0f) * 65535.0f;
            }
            if (pb) {
              const std::uint16_t* q = pb->data() + 4 * local;
              for (std::size_t k = 0; k < 4 * n; ++k) vb[k] = static_cast<float>(q[k]);
            } else {
              for (std::size_t k = 0; k < 4 * n; ++k) vb[k] = std::clamp(skin[k], 0.0f, 1.0f) * 65535.0f;
            }
            for (std::size_t k = 0; k < 4 * n; ++k)
              o[k] = static_cast<std::uint16_t>(static_cast<int>(va[k] * s + vb[k] * t + 0.5f));
          } else if (job.map == 1) {
            const auto* pa = static_cast<const std::vector<std::uint16_t>*>(job.a);
            const auto* pb = static_cast<const std::vector<std::uint16_t>*>(job.b);
            std::uint16_t* o = static_cast<std::uint16_t*>(job.out) + local;
            const float ca = std::clamp(ra, 0.0f, 1.0f) * 65535.0f, cb = std::clamp(rb, 0.0f, 1.0f) * 65535.0f;
            for (std::size_t k = 0; k < n; ++k) {
              const float va = pa ? static_cast<float>((*pa)[local + k]) : ca;
              const float vb = pb ? static_cast<float>((*pb)[local + k]) : cb;
              o[k] = static_cast<std::uint16_t>(static_cast<int>(va * s + vb * t + 0.5f));
            }
          } else {
            const auto* pa = static_cast<const std::vector<float>*>(job.a);
            const auto* pb = static_cast<const std::vector<float>*>(job.b);
            float* o = static_cast<float*>(job.out) + local;
            for (std::size_t k = 0; k < n; ++k) {
              const float va = pa ? (*pa)[local + k] : 0.0f;
              const float vb = pb ? (*pb)[local + k] : 0.0f;
              o[k] = va * s + vb * t;
            }
          }
        }
      },
      1);
}

}  // namespace forensim
