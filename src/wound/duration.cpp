#include "wound/duration.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.hpp"

namespace forensim {

double parse_duration(const std::string& text, const std::string& source) {
  if (text.empty()) throw InputError(source, "\"\"", "empty duration");
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin) throw InputError(source, "'" + text + "'", "expected a number followed by s, min, h, d or w");
  const std::string unit(end);
  double scale = 0.0;
  if (unit.empty() || unit == "s") {
    scale = 1.0;
  } else if (unit == "min" || unit == "m") {
    scale = 60.0;
  } else if (unit == "h") {
    scale = 3600.0;
  } else if (unit == "d") {
    scale = 86400.0;
  } else if (unit == "w") {
    scale = 7.0 * 86400.0;
  } else {
    throw InputError(source, "'" + text + "'", "unknown unit '" + unit + "' (use s, min, h, d or w)");
  }
  if (!std::isfinite(value) || value < 0.0 || value > 1e6) {
    throw InputError(source, "'" + text + "'", "duration must be a finite value in [0, 1e6] units");
  }
  return value * scale;
}

std::vector<double> parse_durations(const std::string& list, const std::string& source) {
  std::vector<double> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = list.find(',', start);
    const std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    out.push_back(parse_duration(item, source));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

std::string format_injury_time(double seconds) {
  struct Unit {
    double s;
    const char* name;
  };
  const Unit units[] = {{7.0 * 86400.0, "w"}, {86400.0, "d"}, {3600.0, "h"}, {60.0, "min"}, {1.0, "s"}};
  for (const auto& u : units) {
    // Weeks only from two weeks on: "10d" reads better than "1.43w".
    const double from = u.s == 7.0 * 86400.0 ? 2.0 * u.s : u.s;
    if (seconds >= from || u.s == 1.0) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%g%s", std::round(seconds / u.s * 100.0) / 100.0, u.name);
      return buf;
    }
  }
  return "0s";
}

}  // namespace forensim
