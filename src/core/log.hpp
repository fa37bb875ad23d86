#pragma once
/// Logging through spdlog (fmt-style formatting). forensim logs to stderr; results go to files.

#include <spdlog/spdlog.h>

#include <string>

namespace forensim {

/// Sets the log level by name: "trace", "debug", "info", "warn", "error", "off".
void set_log_level(const std::string& level);

}  // namespace forensim
