#pragma once
/// A craniofacial reconstruction run from its job, in memory (Kähler, Haber and Seidel 2003): the inputs
/// (reconstruct_inputs.hpp), the warp of the template head onto the skull with the tissue depths and guides
/// (craniofacial/reconstruction.hpp, eq. 1 and section 4.3), and what the job adds to it: the uncertainty ensemble
/// (depths drawn from the table's SDs), the evaluation against the CT's real face, and the expressions as morph
/// targets (section 5). reconstruction_provenance() records where every part came from. The command line and
/// the demo write the result (maps, pictures, files); the skull editor's sessions keep the Reconstruction to
/// edit it.

#include <memory>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/timer.hpp"
#include "craniofacial/face_evaluation.hpp"
#include "craniofacial/reconstruction.hpp"
#include "craniofacial/reconstruction_uncertainty.hpp"
#include "geometry/tri_mesh.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "reconstruct/reconstruct_inputs.hpp"
#include "reconstruct/reconstruct_job.hpp"

namespace forensim {

struct ReconstructedFace {
  ReconstructInputs inputs;
  /// The warp (it refers to inputs.fitted, which it shares the life of).
  std::unique_ptr<Reconstruction> reconstruction;
  /// The reconstructed skin (mm, the skull's frame), with the vertex field "uncertainty" (mm) when the ensemble
  /// ran.
  TriMesh skin;
  std::optional<ReconstructionUncertainty> uncertainty;
  std::optional<FaceEvaluation> evaluation;
  /// The evaluation's figures with its real face, region and method (null without an evaluation).
  nlohmann::json evaluation_record;
  std::vector<MorphTarget> expressions;  ///< one per job expression, in its order
  Timings timings;                       ///< the inputs' stages, then these
};

/// Runs the job in memory (nothing is written). Throws as prepare_reconstruction, and InputError from the
/// evaluation (no face in the region) and the ensemble (a table without SDs).
ReconstructedFace reconstruct_face(const ReconstructJob& job);

/// The provenance record of a run: template, skull, table, landmarks (with the detection's details), guides
/// (`guides_record`: the guides as the user gave them, or null), expressions, the ensemble's size and seed, the
/// evaluation record and the seed.
nlohmann::json reconstruction_provenance(const ReconstructJob& job, const ReconstructedFace& face,
                                         const nlohmann::json& guides_record);

}  // namespace forensim
