#pragma once
/// Taubin's lambda|mu smoothing: low-pass filtering of a mesh's vertex positions that removes the staircase of
/// iso-surfaces extracted from voxels without the shrinkage of plain Laplacian smoothing.
/// G. Taubin, "A signal processing approach to fair surface design", SIGGRAPH 1995.

#include "geometry/tri_mesh.hpp"

namespace forensim {

/// Runs `iterations` pairs of steps p += lambda * L(p), then p += mu * L(p), where L is the uniform (umbrella)
/// Laplacian: the mean of a vertex's edge neighbours minus the vertex. Needs 0 < lambda < -mu (typically
/// lambda = 0.5, mu = -0.53: pass-band frequency k_PB = 1/lambda + 1/mu ~ 0.1). Topology is unchanged; normals,
/// when present, are recomputed. Throws InputError for lambda <= 0, mu >= 0 or negative iterations.
void taubin_smooth(TriMesh& mesh, int iterations, double lambda = 0.5, double mu = -0.53);

}  // namespace forensim
