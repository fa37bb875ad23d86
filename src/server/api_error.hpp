#pragma once
/// The error a request handler throws to answer with an HTTP status and a JSON body
/// {"error": {"status", "message", "field"}}, where `field` is the JSON pointer of the request value at
/// fault ("/job/strokes/0/radius_mm"), empty when the fault is not in one field.

#include <stdexcept>
#include <string>

namespace forensim {

class ApiError : public std::runtime_error {
 public:
  ApiError(int status, std::string message, std::string field = {})
      : std::runtime_error(message), m_status(status), m_field(std::move(field)) {}
  int status() const { return m_status; }
  const std::string& field() const { return m_field; }

 private:
  int m_status;
  std::string m_field;
};

}  // namespace forensim
