#pragma once
/// Float images: textures, renders, scalar maps. Pixels are interleaved channels (1 to 4), rows top to
/// bottom, (0,0) is the top-left pixel. An image carries the encoding of its values so writers know
/// whether to apply the sRGB transfer curve.

#include <cstddef>
#include <vector>

#include "core/types.hpp"

namespace forensim {

/// What the numbers in an image mean.
enum class PixelEncoding {
  linear,  ///< scene-linear colour (renders before tone mapping, textures for shading); PNG writers sRGB-encode it
  srgb,    ///< display-referred, already sRGB-encoded colour (final pictures); written as is
  data,    ///< non-colour data (normals, heights, roughness, masks); written as is, never converted
};

/// How samples outside [0, width) x [0, height) are found.
enum class WrapMode { clamp, wrap };

/// Largest number of pixels (width * height) an image may have: 2^28 (16384 x 16384).
inline constexpr std::size_t max_image_pixels = std::size_t{1} << 28;

class Image {
 public:
  Image() = default;
  /// width x height pixels of `channels` (1..4) channels, all set to `value`. Throws InputError for
  /// negative sizes, channel counts outside 1..4 or more than max_image_pixels pixels.
  Image(int width, int height, int channels, float value = 0.0f, PixelEncoding encoding = PixelEncoding::linear);

  int width() const { return m_width; }
  int height() const { return m_height; }
  int channels() const { return m_channels; }
  bool empty() const { return m_width == 0 || m_height == 0; }
  PixelEncoding encoding() const { return m_encoding; }
  void set_encoding(PixelEncoding encoding) { m_encoding = encoding; }

  /// Channel c of pixel (x, y); no bounds check beyond a debug assertion.
  float& at(int x, int y, int c = 0) { return m_data[index(x, y, c)]; }
  float at(int x, int y, int c = 0) const { return m_data[index(x, y, c)]; }
  /// Pointer to the `channels()` values of pixel (x, y).
  float* pixel(int x, int y) { return m_data.data() + index(x, y, 0); }
  const float* pixel(int x, int y) const { return m_data.data() + index(x, y, 0); }
  /// Pixel as RGBA: grey is replicated to RGB, a missing alpha reads 1.
  Vec4f rgba(int x, int y) const;
  /// Sets pixel (x, y) from RGBA: 1-channel images take the Rec. 709 luminance, 2-channel luminance and alpha.
  void set_rgba(int x, int y, const Vec4f& value);
  /// All values, row-major, channels interleaved (width * height * channels).
  const std::vector<float>& data() const { return m_data; }
  std::vector<float>& data() { return m_data; }

  /// Sets every channel of every pixel to `value`.
  void fill(float value);
  /// Sets every pixel to `value` (RGBA, converted as in set_rgba).
  void fill(const Vec4f& value);

  /// Bilinear sample of channel c at continuous pixel coordinates (x, y), pixel centres at i + 0.5.
  float sample(double x, double y, int c, WrapMode wrap = WrapMode::clamp) const;
  /// Bilinear RGBA sample at texture coordinates (u right, v up, as in OBJ/OpenGL): u = 0 is the left
  /// edge, v = 0 the bottom edge.
  Vec4f sample_uv(const Vec2& uv, WrapMode wrap = WrapMode::wrap) const;

  /// The w x h block whose top-left pixel is (x, y), clipped to the image.
  Image crop(int x, int y, int w, int h) const;
  /// Copies `source` with its top-left pixel at (x, y), clipped; channels are converted as in set_rgba.
  /// With `blend` the source alpha composites it over this image ("over" operator).
  void paste(const Image& source, int x, int y, bool blend = false);
  /// Resampled copy of w x h pixels: box filter when shrinking, bilinear when enlarging (per axis).
  Image resized(int w, int h) const;
  /// Copy with `channels` channels (grey <-> RGB <-> RGBA as in set_rgba).
  Image with_channels(int channels) const;

 private:
  std::size_t index(int x, int y, int c) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(m_width) + static_cast<std::size_t>(x)) *
               static_cast<std::size_t>(m_channels) +
           static_cast<std::size_t>(c);
  }

  int m_width = 0;
  int m_height = 0;
  int m_channels = 0;
  PixelEncoding m_encoding = PixelEncoding::linear;
  std::vector<float> m_data;
};

}  // namespace forensim
