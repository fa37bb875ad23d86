#pragma once
/// Exact, locale-independent number text for the tet_io writers: doubles in the shortest decimal form that
/// reads back to the same bits (std::to_chars), so ASCII files round-trip without loss.

#include <cstdint>
#include <string>

namespace forensim {

/// Appends `value` in shortest round-trip decimal form ("0.1", "1e-300", "-2").
void append_double(std::string& out, double value);
/// Appends `value` as a decimal float that reads back to the same float ("0.1" for 0.1f).
void append_float(std::string& out, float value);
/// Appends a decimal integer.
void append_integer(std::string& out, std::int64_t value);

}  // namespace forensim
