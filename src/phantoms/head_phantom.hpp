#pragma once
/// The `head` phantom: an adult head and neck with forehead, brow ridge, eye sockets with closed lids, nose,
/// lips, chin, cheeks and ears, over a skull (cranial vault, orbits, nasal aperture, zygomatic arches, maxilla,
/// mandible, teeth) and cervical spine. Millimetres, patient LPS axes as in CT: x toward the patient's left,
/// y posterior, z superior; the face looks toward -y. Head breadth 150 mm, length 196 mm, vertex to chin
/// 225 mm; soft-tissue depths over the skull near the published means (about 5 to 6 mm at glabella and nasion,
/// 10 to 12 mm at the lips and chin; see reference/tissue-depth.md).

#include "phantoms/phantom.hpp"

namespace forensim {

class HeadPhantom final : public Phantom {
 public:
  HeadPhantom();
  std::string name() const override { return "head"; }
  double skin_distance(const Vec3& p) const override;
  double bone_distance(const Vec3& p) const override;
  BoundingBox bounds() const override;
  const std::vector<std::string>& part_names() const override { return m_part_names; }
  int part_at(const Vec3& p) const override;

 private:
  std::vector<std::string> m_part_names;
};

}  // namespace forensim
