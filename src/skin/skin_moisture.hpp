#pragma once
/// The moisture ratio m of eqs. 37 to 39 at the skin vertices, from the moisture of the tet volume's nodes:
/// each skin vertex reads the volume at its tracking point (a boundary face's three nodes with barycentric
/// weights, body/tracking.hpp) and divides by the initial moisture content.

#include <vector>

#include "core/types.hpp"

namespace forensim {

/// m_i = clamp(sum_k weights[i][k] phi[face_nodes[i][k]] / phi_0, 0, 1) for each skin vertex i into `ratio`
/// (resized to #S). `face_nodes`, `weights`: #S tracking faces and weights (TrackingConnections);
/// `node_moisture`: #N moisture contents phi of the volume's nodes (kg/kg dry basis or any unit of phi_0);
/// `initial_moisture`: phi_0 (> 0) of the flesh. Throws InputError for mismatched sizes, a node index out of
/// range or phi_0 <= 0.
void skin_moisture_ratio(const std::vector<Tri>& face_nodes, const std::vector<Vec3>& weights,
                         const std::vector<double>& node_moisture, double initial_moisture, std::vector<double>& ratio);

}  // namespace forensim
