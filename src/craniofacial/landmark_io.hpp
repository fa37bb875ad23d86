#pragma once
/// Landmark files: 3D Slicer markups JSON (.mrk.json), the common interchange format for landmarks on skulls,
/// and plain CSV tables (name, x, y, z). Whatever the file's coordinate system, landmarks come in and go out
/// of forensim as LPS millimetres (x towards the subject's left, y posterior, z superior; the frame of CT
/// volumes in src/volume); RAS files (x right, y anterior) are converted by negating x and y.
///
/// Slicer markups (schema markups-schema-v1.0.3): a top-level object with a "markups" array; forensim reads
/// every entry whose "type" is "Fiducial" (other markup types are skipped), its "coordinateSystem" ("LPS" or
/// "RAS"; LPS when absent, as Slicer assumes), "coordinateUnits" ("mm" when absent; other units are rejected)
/// and its "controlPoints", each with "label", "position" [x, y, z] and "positionStatus" (points that are not
/// "defined" have no position and are skipped). forensim writes a control point's source and confidence into
/// its "description" ("zygion, left; source=detected; confidence=0.82") and reads them back from there.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craniofacial/landmark_set.hpp"

namespace forensim {

/// Patient coordinate systems of landmark files.
enum class CoordinateSystem {
  lps,  ///< x left, y posterior, z superior (DICOM, ITK, forensim)
  ras,  ///< x right, y anterior, z superior (Slicer's internal frame, NIfTI)
};

/// "LPS" or "RAS".
std::string to_string(CoordinateSystem system);
/// Position in LPS of a point given in `system`.
Vec3 to_lps(const Vec3& point, CoordinateSystem system);
/// Position in `system` of an LPS point (its own inverse: RAS <-> LPS negates x and y).
Vec3 from_lps(const Vec3& point_lps, CoordinateSystem system);

/// What to do with landmark names read from files.
enum class LandmarkNaming {
  canonical,  ///< resolve through the built-in vocabulary ("Nasion" -> "n", "zy-l" -> "zy_L"); unknown -> InputError
  keep,       ///< keep labels as written (they must still be non-empty and unique)
};

struct LandmarkReadOptions {
  LandmarkNaming naming = LandmarkNaming::canonical;
  /// Coordinate system of CSV files. When not set: a "# coordinate system: RAS" (or LPS) comment line in the
  /// file decides, else LPS. Markups files always say theirs.
  std::optional<CoordinateSystem> csv_coordinate_system;
};

struct LandmarkWriteOptions {
  CoordinateSystem coordinate_system = CoordinateSystem::lps;  ///< system of the written coordinates
};

/// Parses markups JSON text (`source` names it in messages). Landmarks get source `imported` and confidence 1
/// unless their description carries forensim's "source=..; confidence=.." fields. Throws InputError(source,
/// location, problem) for invalid JSON (with line and column), a missing or non-array "markups", no Fiducial
/// markup, an unknown coordinate system or unit, a position that is not three finite numbers, an empty,
/// unknown (with "did you mean") or duplicate label.
LandmarkSet parse_markups_json(const std::string& text, const std::string& source,
                               const LandmarkReadOptions& options = {});
/// Markups JSON text of one Fiducial markup holding every landmark of `set`.
std::string markups_json_text(const LandmarkSet& set, const LandmarkWriteOptions& options = {});

/// Parses a landmark CSV table: header with columns name, x, y, z (required) and source, confidence
/// (optional), then one row per landmark. Throws InputError naming line and field for a malformed table,
/// a non-finite coordinate, an unknown or duplicate name.
LandmarkSet parse_landmark_csv(const std::string& text, const std::string& source,
                               const LandmarkReadOptions& options = {});
/// CSV text with columns name, x, y, z, source, confidence and a "# coordinate system: .." comment line.
std::string landmark_csv_text(const LandmarkSet& set, const LandmarkWriteOptions& options = {});

/// Reads a landmark file chosen by its name: *.mrk.json / *.json -> markups, *.csv -> CSV. The set is named
/// after the file. Throws IoError when it cannot be read, InputError for other extensions (Slicer's legacy
/// .fcsv is refused with a hint to save it as .mrk.json) and malformed content.
LandmarkSet read_landmarks(const std::filesystem::path& path, const LandmarkReadOptions& options = {});
/// Writes a landmark file chosen by its name (as read_landmarks) atomically (temporary file + rename).
/// Throws InputError for an unknown extension, IoError when it cannot be written.
void write_landmarks(const std::filesystem::path& path, const LandmarkSet& set,
                     const LandmarkWriteOptions& options = {});

}  // namespace forensim
