#include "server/skull_templates.hpp"

#include "core/error.hpp"

namespace forensim {

std::vector<std::string> SkullTemplates::names() {
  return {"full", "coarse"};
}

TemplateHeadOptions template_head_options(const std::string& detail) {
  TemplateHeadOptions o;
  if (detail == "coarse") {
    o.skin_voxel_mm = 3.0;
    o.skin_edge_mm = 6.0;
    o.skull_voxel_mm = 3.0;
    o.remesh_iterations = 2;
    o.uv_resolution = 512;
  } else if (detail != "full") {
    throw InputError("template detail", detail, "unknown (known: full, coarse)");
  }
  return o;
}

std::shared_ptr<const TemplateHead> SkullTemplates::get(const std::string& detail) {
  const TemplateHeadOptions options = template_head_options(detail);
  Entry& e = detail == "coarse" ? m_coarse : m_full;
  std::call_once(e.once, [&] { e.head = std::make_shared<const TemplateHead>(make_template_head(options)); });
  return e.head;
}

}  // namespace forensim
