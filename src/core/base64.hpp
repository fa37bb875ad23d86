#pragma once
/// Base64 (RFC 4648, standard alphabet, '=' padding): VTK XML inline binary arrays, pictures embedded in HTML.

#include <optional>
#include <string>
#include <string_view>

namespace forensim {

/// Encodes `bytes` with padding; the output length is 4 * ceil(size / 3).
std::string base64_encode(std::string_view bytes);

/// Decodes one padded base64 chunk (no whitespace; length a multiple of 4, '=' only at its end). Returns
/// nullopt and sets `bad_char` to the offending character offset (or to the length when the length is wrong)
/// when `text` is not valid base64.
std::optional<std::string> base64_decode(std::string_view text, std::size_t& bad_char);

/// Characters of base64 text that encode `bytes` bytes (with padding).
constexpr std::size_t base64_length(std::size_t bytes) {
  return (bytes + 2) / 3 * 4;
}

}  // namespace forensim
