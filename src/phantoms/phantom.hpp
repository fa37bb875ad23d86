#pragma once
/// Procedural body parts: forensim's built-in inputs, so every command works with no data. A phantom is a
/// pair of signed distance functions (skin and bone; millimetres, negative inside) plus named parts (fingers,
/// palm, forearm; nose, ears, neck) that results are reported by. Meshing them (surfaces, tetrahedra) is the
/// job of the geometry and volume modules.

#include <memory>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/bounding_box.hpp"

namespace forensim {

class Phantom {
 public:
  virtual ~Phantom() = default;
  /// "arm", "head".
  virtual std::string name() const = 0;
  /// Signed distance to the skin surface (mm, negative inside the body).
  virtual double skin_distance(const Vec3& p) const = 0;
  /// Signed distance to the bone surfaces (mm, negative inside bone). Bone lies inside the skin.
  virtual double bone_distance(const Vec3& p) const = 0;
  /// A box that encloses the skin with a small margin.
  virtual BoundingBox bounds() const = 0;
  /// Names of the parts, indexed by part_at().
  virtual const std::vector<std::string>& part_names() const = 0;
  /// Index of the part a point inside the body belongs to.
  virtual int part_at(const Vec3& p) const = 0;
};

/// Names of the built-in phantoms.
std::vector<std::string> phantom_names();
/// Creates a built-in phantom by name. Throws InputError for an unknown name (listing the known ones).
std::unique_ptr<Phantom> make_phantom(const std::string& name);

}  // namespace forensim
