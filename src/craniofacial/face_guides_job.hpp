#pragma once
/// The nose and mouth guides (face_guides.hpp) as a job-file object, read and written the same way by
/// `forensim reconstruct` (the "guides" key of its job, or --guides FILE) and by `forensim serve`'s skull
/// editor: the FaceGuides fields by name, vectors as [x, y, z] in mm, the rest numbers (mm, or the factor).

#include <nlohmann/json.hpp>

#include "core/job.hpp"
#include "craniofacial/face_guides.hpp"

namespace forensim {

/// Reads the guides object. Throws JobError naming the key for wrong types, vectors that are not three finite
/// numbers, coordinates beyond 1e6 mm and values out of range (alar_offset_mm in [0, 50], krogman_factor in
/// [0, 20]).
FaceGuides read_face_guides(const JobNode& node);
/// True when at least one guide value is given in `guides`.
bool any_guide(const FaceGuides& guides);
/// The guides as the object read_face_guides() reads (only the values that are set, and the axes and factors).
nlohmann::json face_guides_json(const FaceGuides& guides);

}  // namespace forensim
