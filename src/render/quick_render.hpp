#pragma once
/// One-call pictures of a mesh for quick looks: studio lights, framed from a named view.

#include <string>

#include "geometry/tri_mesh.hpp"
#include "image/image.hpp"
#include "render/camera.hpp"
#include "render/render_settings.hpp"

namespace forensim {

/// Renders `mesh` from the named view ("front", "three_quarter", ...) with the studio rig: vertex colours
/// if it has them, else neutral clay. `axes` gives the subject's up and front (LPS by default).
/// Throws InputError for an unknown view or an invalid mesh.
Image render_mesh(const TriMesh& mesh, const RenderSettings& settings, const std::string& view = "three_quarter",
                  const ViewAxes& axes = {});

}  // namespace forensim
