#include "skin/skin_moisture.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace forensim {

void skin_moisture_ratio(const std::vector<Tri>& face_nodes, const std::vector<Vec3>& weights,
                         const std::vector<double>& node_moisture, double initial_moisture,
                         std::vector<double>& ratio) {
  const std::string src = "skin moisture";
  require_input(face_nodes.size() == weights.size(), src, "weights",
                "has " + std::to_string(weights.size()) + " entries for " + std::to_string(face_nodes.size()) +
                    " tracking faces");
  require_input(std::isfinite(initial_moisture) && initial_moisture > 0.0, src, "initial_moisture", "must be positive");
  const auto nodes = static_cast<Index>(node_moisture.size());
  // The message is built only for a bad node: this runs every frame over every skin vertex.
  for (std::size_t i = 0; i < face_nodes.size(); ++i)
    for (Index n : face_nodes[i])
      if (n < 0 || n >= nodes)
        throw InputError(src, "face_nodes[" + std::to_string(i) + "]",
                         "node " + std::to_string(n) + " is not one of the " + std::to_string(nodes) + " nodes");
  ratio.resize(face_nodes.size());
  parallel_for(0, face_nodes.size(), [&](std::size_t i) {
    double phi = 0.0;
    for (int k = 0; k < 3; ++k) phi += weights[i][k] * node_moisture[static_cast<std::size_t>(face_nodes[i][k])];
    ratio[i] = std::clamp(phi / initial_moisture, 0.0, 1.0);
  });
}

}  // namespace forensim
