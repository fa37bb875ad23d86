#include "core/error.hpp"

#include <utility>

namespace forensim {
namespace {
std::string join_input_message(const std::string& source, const std::string& location, const std::string& problem) {
  std::string message = source;
  if (!location.empty()) message += ":" + location;
  message += ": " + problem;
  return message;
}
}  // namespace

InputError::InputError(std::string source, std::string location, std::string problem)
    : Error(join_input_message(source, location, problem), ErrorKind::input),
      m_source(std::move(source)),
      m_location(std::move(location)),
      m_problem(std::move(problem)) {}

JobError::JobError(std::string source, std::string key_path, std::string problem)
    : Error(source + ": " + (key_path.empty() ? std::string("/") : key_path) + ": " + problem, ErrorKind::job),
      m_key_path(std::move(key_path)) {}

IoError::IoError(const std::string& path, const std::string& problem) : Error(path + ": " + problem, ErrorKind::io) {}

}  // namespace forensim
