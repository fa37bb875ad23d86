#include "server/skull_templates.hpp"

#include "core/error.hpp"

namespace forensim {

std::vector<std::string> SkullTemplates::names() {
  return {"full", "coarse"};
}

std::shared_ptr<const TemplateHead> SkullTemplates::get(const std::string& detail) {
  const TemplateHeadOptions options = template_head_options(detail);
  Entry& e = detail == "coarse" ? m_coarse : m_full;
  std::call_once(e.once, [&] { e.head = std::make_shared<const TemplateHead>(make_template_head(options)); });
  return e.head;
}

}  // namespace forensim
