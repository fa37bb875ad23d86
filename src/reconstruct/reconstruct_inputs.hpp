#pragma once
/// The stages of a craniofacial reconstruction before the warp (Kähler, Haber and Seidel 2003, section 3):
/// the tissue depths from the job's table and group, the skull (built-in, mesh file or CT volume), the template
/// head, and the skull landmarks (the template's own, a file, or detected by registering the template's skull
/// onto the skull, which also completes a partial scan), with the template carried onto the skull by that
/// registration (template_carry.hpp). `forensim reconstruct`, the demo and the skull editor's sessions all start
/// here, so one skull gives one face wherever it is reconstructed.
///
/// Order (the checks that need no geometry first, so bad input fails in a tenth of a second): the table and
/// group, the expression names, the landmark mode, a landmark file, the skull's file; then the template is
/// built beside the skull's extraction and the landmark detection (they are independent).

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/timer.hpp"
#include "craniofacial/head_frame.hpp"
#include "craniofacial/landmark_detection.hpp"
#include "craniofacial/landmark_set.hpp"
#include "craniofacial/reconstruction.hpp"
#include "craniofacial/skull_completion.hpp"
#include "craniofacial/skull_input.hpp"
#include "craniofacial/template_head.hpp"
#include "craniofacial/tissue_depth_table.hpp"
#include "reconstruct/reconstruct_job.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

/// Everything the warp takes, read and checked. Positions in mm in the skull's frame.
struct ReconstructInputs {
  TissueDepthTable table;
  TissueDepths depths;                         ///< the job's group (and build variant)
  std::string build_method;                    ///< how the build variant was made; empty for the group's own values
  Skull skull;                                 ///< completed where landmarks lay outside a partial scan
  std::optional<ScalarGrid> volume;            ///< a CT skull's volume (the evaluation takes the real face from it)
  std::shared_ptr<const TemplateHead> head;    ///< the template as built, read or given
  std::shared_ptr<const TemplateHead> fitted;  ///< the head the warp starts from: `head`, or it carried onto the skull
  bool carried = false;                        ///< fitted is head carried by the detection's registration
  bool template_from_file = false;             ///< the job's template_file was read
  std::optional<LandmarkDetection> detection;  ///< with automatic landmarks
  std::optional<SkullCompletion> completion;   ///< when detected landmarks lay outside the scan
  std::string landmark_mode;                   ///< "template", "auto" or the landmark file's path
  LandmarkSet landmarks;                       ///< the skull landmarks of the warp
  std::string landmark_origin;                 ///< where they came from, in words (provenance)
  std::optional<HeadFrame> known_frame;        ///< the skull's head frame where the landmarks give it
  ReconstructionOptions options;               ///< interpolated landmarks and guides (measured ones merged in)
  nlohmann::json measured_guides;              ///< null unless the job measures the guides
  std::vector<std::string> messages;           ///< lines for the user: landmarks left out, guides measured
  Timings timings;                             ///< the stages' seconds, in order
};

/// Reads and checks a job's inputs and runs the stages before the warp. `prebuilt`: a template head already
/// built at the job's template_detail (the skull editor keeps one per detail), used instead of building one;
/// the job's template_file must then be empty. Throws InputError (unknown table or group, unknown or repeated
/// expression, "template" landmarks on a skull not in the template's frame, evaluation without a CT), IoError
/// (missing or unreadable file), JobError and NumericError from the stages; std::invalid_argument for a
/// prebuilt head with a template_file.
ReconstructInputs prepare_reconstruction(const ReconstructJob& job,
                                         std::shared_ptr<const TemplateHead> prebuilt = nullptr);

}  // namespace forensim
