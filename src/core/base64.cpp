#include "core/base64.hpp"

#include <array>

namespace forensim {
namespace {
constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

constexpr std::array<signed char, 256> make_inverse() {
  std::array<signed char, 256> inverse{};
  for (auto& v : inverse) v = -1;
  for (int i = 0; i < 64; ++i) inverse[static_cast<unsigned char>(alphabet[i])] = static_cast<signed char>(i);
  return inverse;
}
constexpr std::array<signed char, 256> inverse = make_inverse();
}  // namespace

std::string base64_encode(std::string_view bytes) {
  std::string out;
  out.reserve(base64_length(bytes.size()));
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += alphabet[(v >> 6) & 63];
    out += alphabet[v & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (rest == 2) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += alphabet[(v >> 18) & 63];
    out += alphabet[(v >> 12) & 63];
    out += rest == 2 ? alphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::optional<std::string> base64_decode(std::string_view text, std::size_t& bad_char) {
  if (text.size() % 4 != 0) {
    bad_char = text.size();
    return std::nullopt;
  }
  std::string out;
  out.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    int padding = 0;
    unsigned v = 0;
    for (std::size_t k = 0; k < 4; ++k) {
      const char c = text[i + k];
      int digit = inverse[static_cast<unsigned char>(c)];
      if (c == '=' && last && k >= 2 && (k == 3 || text[i + 3] == '=')) {
        ++padding;
        digit = 0;
      } else if (digit < 0 || padding > 0) {
        bad_char = i + k;
        return std::nullopt;
      }
      v = (v << 6) | static_cast<unsigned>(digit);
    }
    out += static_cast<char>((v >> 16) & 255);
    if (padding < 2) out += static_cast<char>((v >> 8) & 255);
    if (padding < 1) out += static_cast<char>(v & 255);
  }
  return out;
}

}  // namespace forensim
