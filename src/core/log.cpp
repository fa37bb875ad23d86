#include "core/log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

#include "core/error.hpp"

namespace forensim {

void set_log_level(const std::string& level) {
  static bool configured = false;
  if (!configured) {
    auto logger = spdlog::stderr_color_mt("forensim");
    logger->set_pattern("%^[%l]%$ %v");
    spdlog::set_default_logger(logger);
    configured = true;
  }
  const auto parsed = spdlog::level::from_str(level);
  if (parsed == spdlog::level::off && level != "off") {
    throw Error("unknown log level '" + level + "' (use trace, debug, info, warn, error or off)", ErrorKind::usage);
  }
  spdlog::set_level(parsed);
}

}  // namespace forensim
