#pragma once
/// The `arm` phantom: a right forearm and hand, palm down, with radius and ulna, carpal block, metacarpals
/// and phalanges inside. Adult proportions in millimetres (forearm from 5 cm below the elbow, 205 mm to the
/// wrist; palm 95 mm; middle finger 95 mm). Frame: x distal (toward the fingertips), y toward the thumb
/// (radial side), z dorsal (back of the hand up). The fingers are about 18 mm thick and the forearm 60 to
/// 80 mm, so extremities dry first as in Frerichs et al. 2020 (section 9).

#include <array>

#include "phantoms/phantom.hpp"

namespace forensim {

class ArmPhantom final : public Phantom {
 public:
  ArmPhantom();
  std::string name() const override { return "arm"; }
  double skin_distance(const Vec3& p) const override;
  double bone_distance(const Vec3& p) const override;
  BoundingBox bounds() const override;
  const std::vector<std::string>& part_names() const override { return m_part_names; }
  int part_at(const Vec3& p) const override;

  /// A finger as a chain of joint centres (MCP or CMC, then the next joints, then the tip) with skin radii.
  struct Digit {
    std::string name;
    std::array<Vec3, 4> joints;   ///< base joint, two interphalangeal joints (one for the thumb, repeated), tip
    std::array<double, 4> radii;  ///< skin radius at each joint (mm)
    Vec3 metacarpal_base;         ///< proximal end of the metacarpal, at the carpus
  };
  const std::vector<Digit>& digits() const { return m_digits; }

 private:
  std::vector<Digit> m_digits;
  std::vector<std::string> m_part_names;
};

}  // namespace forensim
