#pragma once
/// Times after injury in real units, as users write them: "90s", "10min", "36h", "3d", "2w" (a bare number
/// is seconds). Wound timelines place their key positions at physiological times (Linnenbank 2015,
/// chapter 2.1: minutes for hemostasis, days for the scab, weeks for maturation).

#include <string>
#include <vector>

namespace forensim {

/// Seconds in "<number><unit>" with unit s, min, h, d or w (or none = s); the number may have a fraction.
/// Throws InputError(source, text, problem) for anything else, negative or non-finite values.
double parse_duration(const std::string& text, const std::string& source = "duration");

/// Comma-separated durations ("1h,36h,5d") in seconds, in the order given.
std::vector<double> parse_durations(const std::string& list, const std::string& source = "durations");

/// Short human form of seconds in the largest unit that gives a number >= 1 ("36h", "2.5d", "10min").
std::string format_injury_time(double seconds);

}  // namespace forensim
