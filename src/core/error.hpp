#pragma once
/// forensim's exception hierarchy. Every error that crosses the library boundary is a forensim::Error
/// whose message names the input (file, job key, argument) and what is wrong with it. The CLI maps each
/// kind to its own exit code (see exit_code()).

#include <cstdint>
#include <stdexcept>
#include <string>

namespace forensim {

/// Kinds of failure, each with a distinct process exit code.
enum class ErrorKind : int {
  generic = 1,      ///< anything else
  usage = 2,        ///< bad command-line arguments
  input = 3,        ///< malformed, hostile or invalid input data (files, values)
  job = 4,          ///< invalid job file (unknown key, wrong type, out-of-range value)
  io = 5,           ///< a file or folder could not be read or written
  numeric = 6,      ///< a solver failed to converge or produced non-finite values
  cancelled = 130,  ///< interrupted by the user (SIGINT); a checkpoint may allow resuming
};

/// Base of all forensim exceptions.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, ErrorKind kind = ErrorKind::generic)
      : std::runtime_error(message), m_kind(kind) {}
  ErrorKind kind() const { return m_kind; }
  /// Process exit code for this error.
  int exit_code() const { return static_cast<int>(m_kind); }

 private:
  ErrorKind m_kind;
};

/// Bad input data. `source` names the input (a file path or a description such as "skin mesh"),
/// `location` where in it ("line 12", "byte 4096", "triangle 17"; may be empty), `problem` what is wrong.
class InputError : public Error {
 public:
  InputError(std::string source, std::string location, std::string problem);
  const std::string& source() const { return m_source; }
  const std::string& location() const { return m_location; }
  const std::string& problem() const { return m_problem; }

 private:
  std::string m_source, m_location, m_problem;
};

/// Invalid job description; `key_path` is the JSON path of the offending key ("/environment/humidity").
class JobError : public Error {
 public:
  JobError(std::string source, std::string key_path, std::string problem);
  const std::string& key_path() const { return m_key_path; }

 private:
  std::string m_key_path;
};

/// A file or folder could not be opened, read, written or renamed.
class IoError : public Error {
 public:
  IoError(const std::string& path, const std::string& problem);
};

/// A numerical method failed (no convergence, singular matrix, non-finite values).
class NumericError : public Error {
 public:
  explicit NumericError(const std::string& message) : Error(message, ErrorKind::numeric) {}
};

/// A long run was interrupted by the user.
class CancelledError : public Error {
 public:
  explicit CancelledError(const std::string& message) : Error(message, ErrorKind::cancelled) {}
};

/// Throws InputError(source, location, problem) unless `condition` holds. For validating inputs
/// (never use assert for that).
inline void require_input(bool condition, const std::string& source, const std::string& location,
                          const std::string& problem) {
  if (!condition) throw InputError(source, location, problem);
}

}  // namespace forensim
