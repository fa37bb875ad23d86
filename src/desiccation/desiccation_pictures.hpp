#pragma once
/// Pictures of a desiccation run like the paper's Figures 5 and 6 (Frerichs, Vidler and Gatzidis 2020): the
/// moisture field on the outside of the body and on a cut through the bone, and the shrunken volume over
/// the original. The moisture is shown as the water lost, 1 - X / X0, blue (fresh) to red (dry), as in
/// Figure 5; bone is drawn as bone.

#include "desiccation/desiccation_sim.hpp"
#include "image/image.hpp"
#include "render/camera.hpp"
#include "render/render_settings.hpp"

namespace forensim {

/// How to look at the body: axes, the view of the outside, the cut plane normal (through the centre of
/// the volume; the side it points to is removed) and the view of the cut.
struct DesiccationViews {
  ViewAxes axes{Vec3::UnitZ(), Vec3::UnitY()};
  ViewName outside = ViewName::top;
  Vec3 cut_normal = Vec3::UnitZ();
  ViewName cut = ViewName::top;
};

/// Views by layout (BodyPose::views) in a body's axes: "arm" from above (the back of the hand, axes.up), cut
/// across up through radius and ulna; "head" from the left, cut through the midsagittal plane.
DesiccationViews desiccation_views(const std::string& layout, const ViewAxes& axes);

/// The moisture field of `state` on the outside (cut = false) or on the half of the volume behind the cut
/// plane (cut = true), display-referred RGBA.
Image render_moisture(const DesiccationModel& model, const DesiccationState& state, const DesiccationViews& views,
                      bool cut, const RenderSettings& settings);

/// The shrunken body (skin coloured, opaque) under the original outline (semi-transparent), Figure 6.
Image render_shrinkage(const DesiccationModel& model, const DesiccationState& state, const DesiccationViews& views,
                       const RenderSettings& settings);

}  // namespace forensim
