#pragma once
/// Named landmark sets: the points on a skull or a skin that the reconstruction works with, each with where
/// it came from and how sure its placement is. Positions are forensim's internal frame: LPS millimetres
/// (x towards the subject's left, y posterior, z superior), whatever file they were read from.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace forensim {

/// How a landmark got its position.
enum class LandmarkSource {
  detected,  ///< placed automatically (registration of a reference skull, refined by its definition)
  imported,  ///< read from a file (.mrk.json, CSV)
  edited,    ///< placed or moved by a user
};

/// "detected", "imported" or "edited".
std::string to_string(LandmarkSource source);
/// Inverse of to_string(LandmarkSource); throws InputError(source_name, location, ...) for other words.
LandmarkSource parse_landmark_source(const std::string& word, const std::string& source_name,
                                     const std::string& location);

/// One landmark.
struct Landmark {
  std::string name;                                  ///< canonical vocabulary name ("n", "zy_L") or a user's label
  Vec3 position_mm = Vec3::Zero();                   ///< LPS millimetres
  LandmarkSource source = LandmarkSource::imported;  ///< how it was placed
  double confidence = 1.0;                           ///< in [0, 1]: 1 for imported and edited points
};

/// An ordered set of uniquely named landmarks.
class LandmarkSet {
 public:
  LandmarkSet() = default;
  /// A set named `name` (e.g. "skull", "skin", or the file it came from).
  explicit LandmarkSet(std::string name) : m_name(std::move(name)) {}

  const std::string& name() const { return m_name; }
  void set_name(std::string name) { m_name = std::move(name); }

  /// Adds a landmark; throws InputError(this set's name, landmark name, ...) when the name is empty or
  /// already used, the position is not finite or the confidence is outside [0, 1].
  void add(Landmark landmark);
  /// Adds or replaces the landmark with `landmark.name` (same checks as add, except the name may exist).
  void set(Landmark landmark);
  /// Removes a landmark; returns false when there was none of that name.
  bool remove(const std::string& name);

  std::size_t size() const { return m_landmarks.size(); }
  bool empty() const { return m_landmarks.empty(); }
  const std::vector<Landmark>& landmarks() const { return m_landmarks; }
  const Landmark& operator[](std::size_t i) const { return m_landmarks.at(i); }

  bool contains(const std::string& name) const { return index_of(name).has_value(); }
  /// Index of the landmark named `name`, or nullopt.
  std::optional<std::size_t> index_of(const std::string& name) const;
  /// The landmark named `name`, or nullptr.
  const Landmark* find(const std::string& name) const;
  /// The landmark named `name`; throws InputError naming this set when it is absent.
  const Landmark& at(const std::string& name) const;

  /// Names in set order.
  std::vector<std::string> names() const;
  /// Positions in set order (#L points, mm): the plain form the warp takes.
  std::vector<Vec3> positions() const;
  /// Positions of the named landmarks in the given order; throws InputError naming the first absent one.
  std::vector<Vec3> positions(const std::vector<std::string>& names) const;

  /// A copy with every position mapped by `transform` (an affine map, e.g. RAS<->LPS or into a head frame).
  LandmarkSet transformed(const Eigen::Affine3d& transform) const;

 private:
  void check(const Landmark& landmark) const;
  std::string m_name;
  std::vector<Landmark> m_landmarks;
};

}  // namespace forensim
