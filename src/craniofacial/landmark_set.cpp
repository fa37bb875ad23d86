#include "craniofacial/landmark_set.hpp"

#include <cmath>

#include "core/error.hpp"

namespace forensim {

std::string to_string(LandmarkSource source) {
  switch (source) {
    case LandmarkSource::detected:
      return "detected";
    case LandmarkSource::imported:
      return "imported";
    case LandmarkSource::edited:
      return "edited";
  }
  return "imported";
}

LandmarkSource parse_landmark_source(const std::string& word, const std::string& source_name,
                                     const std::string& location) {
  if (word == "detected") return LandmarkSource::detected;
  if (word == "imported") return LandmarkSource::imported;
  if (word == "edited") return LandmarkSource::edited;
  throw InputError(source_name, location,
                   "landmark source '" + word + "' is not one of 'detected', 'imported', 'edited'");
}

void LandmarkSet::check(const Landmark& landmark) const {
  const std::string source = m_name.empty() ? std::string("landmark set") : "landmark set '" + m_name + "'";
  if (landmark.name.empty()) throw InputError(source, "", "landmark with an empty name");
  if (!landmark.position_mm.allFinite()) {
    throw InputError(source, landmark.name, "position is not finite");
  }
  if (!(landmark.confidence >= 0.0 && landmark.confidence <= 1.0)) {
    throw InputError(source, landmark.name, "confidence " + std::to_string(landmark.confidence) + " is outside [0, 1]");
  }
}

void LandmarkSet::add(Landmark landmark) {
  check(landmark);
  if (contains(landmark.name)) {
    throw InputError(m_name.empty() ? std::string("landmark set") : "landmark set '" + m_name + "'", landmark.name,
                     "landmark '" + landmark.name + "' is given twice");
  }
  m_landmarks.push_back(std::move(landmark));
}

void LandmarkSet::set(Landmark landmark) {
  check(landmark);
  if (const auto i = index_of(landmark.name)) {
    m_landmarks[*i] = std::move(landmark);
  } else {
    m_landmarks.push_back(std::move(landmark));
  }
}

bool LandmarkSet::remove(const std::string& name) {
  const auto i = index_of(name);
  if (!i) return false;
  m_landmarks.erase(m_landmarks.begin() + static_cast<std::ptrdiff_t>(*i));
  return true;
}

std::optional<std::size_t> LandmarkSet::index_of(const std::string& name) const {
  for (std::size_t i = 0; i < m_landmarks.size(); ++i) {
    if (m_landmarks[i].name == name) return i;
  }
  return std::nullopt;
}

const Landmark* LandmarkSet::find(const std::string& name) const {
  const auto i = index_of(name);
  return i ? &m_landmarks[*i] : nullptr;
}

const Landmark& LandmarkSet::at(const std::string& name) const {
  if (const Landmark* l = find(name)) return *l;
  throw InputError(m_name.empty() ? std::string("landmark set") : "landmark set '" + m_name + "'", "",
                   "has no landmark '" + name + "'");
}

std::vector<std::string> LandmarkSet::names() const {
  std::vector<std::string> out;
  out.reserve(m_landmarks.size());
  for (const Landmark& l : m_landmarks) out.push_back(l.name);
  return out;
}

std::vector<Vec3> LandmarkSet::positions() const {
  std::vector<Vec3> out;
  out.reserve(m_landmarks.size());
  for (const Landmark& l : m_landmarks) out.push_back(l.position_mm);
  return out;
}

std::vector<Vec3> LandmarkSet::positions(const std::vector<std::string>& names) const {
  std::vector<Vec3> out;
  out.reserve(names.size());
  for (const std::string& n : names) out.push_back(at(n).position_mm);
  return out;
}

LandmarkSet LandmarkSet::transformed(const Eigen::Affine3d& transform) const {
  LandmarkSet out(m_name);
  out.m_landmarks = m_landmarks;
  for (Landmark& l : out.m_landmarks) l.position_mm = transform * l.position_mm;
  return out;
}

}  // namespace forensim
