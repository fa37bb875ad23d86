#pragma once
/// The skin of `forensim mummify` (Frerichs, Vidler and Gatzidis 2020, section 8): where the skin is at each
/// output frame, its colour there (livor mortis start state, then the two-layer shading of section 8.3 driven by
/// the skin's moisture ratio and the hours since the start), and the skin outputs of a run: a .vtu per frame
/// with the colour, moisture and livor fields, baked colour maps when the skin has UVs, the animated GLB, the
/// timeline sheet and the turntable of the final state.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "body/body_model.hpp"
#include "core/types.hpp"
#include "desiccation/desiccation_sim.hpp"
#include "image/image.hpp"
#include "render/camera.hpp"
#include "render/render_settings.hpp"
#include "skin/livor_mortis.hpp"
#include "skin/skin_map_baker.hpp"
#include "skin/skin_shader.hpp"

namespace forensim::cli {

/// Shading settings of a run (job file "skin" object; CLI flags for the common ones).
struct SkinShadingJob {
  Vec3 gravity = Vec3(0, 0, -1);     ///< direction of gravity in the model frame (livor mortis settles along it)
  bool gravity_given = false;        ///< false: the body model's pose gives the gravity (BodyPose::gravity)
  double contact_distance_mm = 3.0;  ///< skin within this of the supporting plane is pressure-pale; < 0: none
  int map_resolution = 512;          ///< texels per side of the baked colour maps (skins with UVs); 0: none
  LivorSettings livor;               ///< gravity is taken from `gravity`
  SkinShadingSettings shading;
};

/// The skin of one output frame.
struct SkinFrame {
  double day = 0.0;
  std::vector<Vec3> positions;   ///< #S mm
  std::vector<double> moisture;  ///< #S moisture ratio m in [0, 1] (eqs. 37 to 39)
  std::vector<Vec4f> colours;    ///< #S linear RGBA
};

/// Rest offsets of the skin from its tracking points, p_i - t_i on the rest volume (#S, mm).
std::vector<Vec3> skin_rest_offsets(const BodyModel& body);

/// Skin vertex positions (#S, mm) for the volume's current node positions (#N, mm): each skin vertex is its
/// tracking point interpolated on the current nodes plus its rest offset, so the skin follows the deforming
/// volume rigidly (the skin of a run with "pbd": false; the position-based skin of mummify_skin_motion.hpp is
/// the default).
std::vector<Vec3> skin_positions_for_frame(const BodyModel& body, const std::vector<Vec3>& rest_offsets,
                                           const std::vector<Vec3>& node_positions);

/// Per-run skin shading: the livor start state, the skin layers and the shader are set up once; a frame is
/// cheap. Output does not depend on the thread count.
class MummifySkin {
 public:
  /// `initial_moisture`: phi_0 of the flesh (kg/kg dry basis). Throws InputError for bad settings.
  MummifySkin(const BodyModel& body, double initial_moisture, const SkinShadingJob& job);

  /// The skin frame of `state` with the skin at `positions` (#S, mm; MummifySkinMotion::positions()): the
  /// moisture ratios at the tracking points and the colours. Throws InputError for a wrong #S.
  SkinFrame frame(const DesiccationState& state, const std::vector<Vec3>& positions) const;
  /// Writes skin/frame_NNNN.vtu (float64, with the fields "colour", "moisture_ratio" and the livor fields) and,
  /// when the skin has UVs, skin/colour_NNNN.png; returns the .vtu's path relative to the run folder.
  std::string write_frame(const std::filesystem::path& run_folder, const SkinFrame& frame, int index) const;

  const LivorState& livor() const { return m_livor; }
  const TriMesh& rest_skin() const { return m_body.skin; }
  bool has_maps() const { return m_baker.has_value(); }

 private:
  const BodyModel& m_body;
  double m_initial_moisture = 1.0;
  SkinShader m_shader;
  LivorState m_livor;
  SkinLayers m_layers;
  std::optional<SkinMapBaker> m_baker;
};

/// Reads back a frame written by MummifySkin::write_frame (the positions and fields are float64, so a frame
/// read back equals the one written). `day` is taken from the caller.
SkinFrame read_skin_frame(const std::filesystem::path& vtu, std::size_t vertex_count, double day);

/// Writes the animated skin as GLB: one node per frame (its own vertex colours, or its baked colour map from
/// `map_pngs` when given), shown in turn by a STEP scale animation, each with one morph target to the next
/// frame's positions whose weight runs from 0 to 1 while it is shown, so the shape moves smoothly and the colour
/// changes per frame. One second of animation per frame; all channels form one animation "drying".
void write_skin_glb(const std::filesystem::path& path, const TriMesh& rest_skin, const std::vector<SkinFrame>& frames,
                    const std::vector<std::string>& map_pngs = {});

/// The skin of `frame` as a mesh with vertex colours and normals.
TriMesh skin_mesh_of_frame(const TriMesh& rest_skin, const SkinFrame& frame);

/// Area-weighted mean skin moisture ratio m of a frame.
double mean_skin_moisture(const TriMesh& rest_skin, const SkinFrame& frame);

/// Timeline sheet: fresh, partly dried and fully dried (the first frame, the one whose mean skin moisture is
/// nearest the middle, and the last) from `view`, captioned with the day and the mean moisture ratio m.
Image skin_timeline_sheet(const TriMesh& rest_skin, const std::vector<SkinFrame>& frames, const ViewAxes& axes,
                          ViewName view, const RenderSettings& settings, const std::string& title);
/// Turntable sheet of the final frame: `count` views around the subject.
Image skin_turntable_sheet(const TriMesh& rest_skin, const SkinFrame& frame, const ViewAxes& axes, int count,
                           const RenderSettings& settings, const std::string& title);

/// Area-weighted mean linear colour of a frame (for run facts and checks).
Vec3 mean_skin_colour(const TriMesh& rest_skin, const SkinFrame& frame);

}  // namespace forensim::cli
