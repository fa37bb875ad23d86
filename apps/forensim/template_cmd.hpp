#pragma once
/// `forensim template build` as a function, for the command and for forensim demo.

#include <optional>
#include <string>

namespace forensim::cli {

struct TemplateArgs {
  std::string ct;                  ///< a CT volume, or "phantom"
  std::string head;                ///< a head mesh
  std::string texture;             ///< the head mesh's base-colour map (else the one embedded in its file)
  std::string skin_landmarks;      ///< skin landmarks on the head mesh (.mrk.json or .csv)
  std::string landmarks = "auto";  ///< the CT skull's landmarks: auto or a file
  std::string unit = "auto";
  double mesh_scale = 0.0;
  std::optional<double> bone_iso;
  std::string detail = "full";  ///< the built-in template carried onto the head
  int texture_size = 1024;
  int picture_size = 768;
  std::string out;
  bool builtin = false;  ///< write the built-in template at `detail` instead
};

/// Builds the template and writes `out` (template.cbor, template.glb, landmarks, template.png, run.json); returns 0.
/// Throws Error (usage), InputError and IoError naming the input.
int run_template_build(const TemplateArgs& args);

}  // namespace forensim::cli
