#pragma once
/// The template heads of `forensim serve`'s skull editor ("full", the CLI's default, about 6 s to build; and
/// "coarse", a quicker, coarser one), each built once on first use and kept for every session (a session's
/// reconstruction refers to its template, so it holds it through the shared pointer). Thread-safe.

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "craniofacial/template_head.hpp"

namespace forensim {

class SkullTemplates {
 public:
  /// "full" and "coarse".
  static std::vector<std::string> names();
  /// The template head of a detail level. Throws InputError for other names.
  std::shared_ptr<const TemplateHead> get(const std::string& detail);

 private:
  struct Entry {
    std::once_flag once;
    std::shared_ptr<const TemplateHead> head;
  };
  Entry m_full, m_coarse;
};

}  // namespace forensim
