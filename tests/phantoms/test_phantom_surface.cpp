#include <gtest/gtest.h>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "phantoms/phantom_surface.hpp"

using namespace forensim;

TEST(PhantomSurface, SkinAndBoneMeshesAreClosedAndBoneIsInside) {
  for (const std::string name : {"arm", "head"}) {
    const auto phantom = make_phantom(name);
    const TriMesh skin = phantom_surface(*phantom, PhantomSurface::skin, 5.0);
    const TriMesh bone = phantom_surface(*phantom, PhantomSurface::bone, 3.0);
    const TopologyReport skin_topology = check_topology(skin);
    EXPECT_TRUE(skin_topology.is_closed() && skin_topology.is_oriented()) << name << ": " << skin_topology.summary();
    EXPECT_TRUE(check_topology(bone).is_closed()) << name;
    EXPECT_GT(enclosed_volume(skin), 4.0 * enclosed_volume(bone)) << name;
    EXPECT_GT(enclosed_volume(bone), 0.0) << name;
    // Surface vertices lie on the zero level set to within half a voxel.
    double worst = 0;
    for (const Vec3& p : skin.positions) worst = std::max(worst, std::abs(phantom->skin_distance(p)));
    EXPECT_LT(worst, 0.5 * 5.0) << name;
  }
}

TEST(PhantomSurface, RejectsBadVoxelSize) {
  const auto arm = make_phantom("arm");
  EXPECT_THROW((void)phantom_surface(*arm, PhantomSurface::skin, 0.0), InputError);
  EXPECT_THROW((void)phantom_surface(*arm, PhantomSurface::skin, -1.0), InputError);
}
