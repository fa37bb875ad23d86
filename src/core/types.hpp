#pragma once
/// Numeric types shared by every forensim module.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>

namespace forensim {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Vec3f = Eigen::Vector3f;
using Vec4f = Eigen::Vector4f;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;
using Index = std::int32_t;        ///< vertex/element index in meshes (2^31 elements are enough)
using Tri = std::array<Index, 3>;  ///< triangle as three vertex indices, counter-clockwise = outward
using Tet = std::array<Index, 4>;  ///< tetrahedron as four vertex indices, positive orientation

}  // namespace forensim
