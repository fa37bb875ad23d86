#include "phantoms/phantom.hpp"

#include "core/error.hpp"
#include "phantoms/arm_phantom.hpp"
#include "phantoms/head_phantom.hpp"

namespace forensim {

std::vector<std::string> phantom_names() {
  return {"arm", "head"};
}

std::unique_ptr<Phantom> make_phantom(const std::string& name) {
  if (name == "arm") return std::make_unique<ArmPhantom>();
  if (name == "head") return std::make_unique<HeadPhantom>();
  std::string known;
  for (const auto& n : phantom_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("phantom name", "", "unknown phantom '" + name + "' (built-in phantoms: " + known + ")");
}

}  // namespace forensim
