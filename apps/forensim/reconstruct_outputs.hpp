#pragma once
/// The run folder of a craniofacial reconstruction, as `forensim reconstruct` and the demo write it.

#include <filesystem>

#include <nlohmann/json.hpp>

#include "reconstruct/reconstruct_job.hpp"

namespace forensim::cli {

/// Runs a reconstruction (reconstruct/reconstruct_face.hpp) and writes it into the run folder `out`: the head
/// (textured GLB with the skull and the expressions as morph targets, OBJ), the skull, skull and skin landmarks
/// (.mrk.json), pictures of the skin over the skull with the depth vectors, the violations, the ensemble's
/// spread and the evaluation where the job asks for them, and provenance.json. Everything is computed before
/// the folder is created, so bad input writes nothing. `resolved_job` is stored in run.json, `guides_record`
/// (the guides as given, or null) in provenance.json. Prints the inputs' messages (landmarks left out, guides
/// measured). Returns the run's facts (given_pairs, interpolated_pairs, correction_pairs, violations_before,
/// violations_after, expressions, the evaluation's figures, seconds_total). Throws the library's errors
/// (InputError, IoError, JobError, NumericError).
nlohmann::json run_reconstruction(const ReconstructJob& job, const std::filesystem::path& out,
                                  const nlohmann::json& resolved_job, const nlohmann::json& guides_record);

}  // namespace forensim::cli
