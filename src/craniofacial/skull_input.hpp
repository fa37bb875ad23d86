#pragma once
/// Skulls as the reconstruction takes them (Kahler et al. 2003, section 3): from a surface scan or any mesh file,
/// or from a CT volume by extracting the bone surface; in millimetres, outward oriented, at most the paper's
/// 250k triangles ("a triangle mesh of the skull model comprised of 50-250k polygons is produced by mesh
/// decimation", Garland and Heckbert 1997).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craniofacial/scan_field_of_view.hpp"
#include "geometry/tri_mesh.hpp"
#include "mesh_io/mesh_import.hpp"
#include "volume/scalar_grid.hpp"

namespace forensim {

struct SkullInputOptions {
  /// Units of mesh files (see MeshImportOptions; scans often come in metres or arbitrary units: give `scale`).
  MeshImportOptions mesh_units;
  /// Volume value at the bone surface. When not set: 126 HU, i.e. 1150 for CT stored as HU + 1024 (the bone
  /// iso-value of VTK's medical examples, also forensim isosurface's; storage is taken as HU + 1024 when the volume
  /// has no value below -100), where the bone is found; with half_maximum_height its surface then moves to the
  /// bone's edge as the CT shows it.
  std::optional<double> bone_iso_value;
  /// Without bone_iso_value: measure the half-maximum height threshold across the 126 HU surface and move that
  /// surface to it, thin bone to the plate model's edge (volume/half_maximum_height); off (default): stay at 126 HU.
  /// On the CT phantom it takes the surface from 1.1 mm outside the bone to within 0.1 mm of it; off by default
  /// until the automatic landmarks' registration is steady enough to show its effect on the headsq face.
  bool half_maximum_height = false;
  /// Taubin smoothing pairs on the CT iso-surface (0 = none); removes the voxel staircase.
  int smoothing_iterations = 0;
  /// Keep at most this many connected components (cranium and mandible when they are separate)...
  int max_components = 2;
  /// ...each with at least this share of the largest component's area (drops loose fragments, vertebrae, the
  /// CT table and noise specks).
  double min_component_area_fraction = 0.05;
  /// Meshes with more triangles are decimated to this many (the paper's upper bound).
  std::size_t max_triangles = 250000;
  /// Below this a note says the skull is coarser than the paper's lower bound (nothing is subdivided).
  std::size_t min_triangles = 50000;
};

/// A skull ready for landmarks.
struct Skull {
  TriMesh mesh;                     ///< mm, counter-clockwise seen from outside
  std::string source;               ///< file the skull came from, or a description
  std::string kind;                 ///< "mesh" or "ct"
  double mm_per_unit = 1.0;         ///< mesh files: scale applied to the file's coordinates
  std::optional<double> iso_value;  ///< CT: the bone iso-value used, or the half-maximum height (stored values)
  /// CT with the measured threshold: the 126 HU iso-value the profiles started from, and the profiles used.
  std::optional<double> seed_iso_value;
  std::size_t threshold_profiles = 0;
  std::size_t input_triangles = 0;  ///< triangles before component selection and decimation
  int components_found = 0;         ///< connected components before selection
  int components_kept = 0;
  std::vector<std::string> notes;  ///< what was done or looks doubtful (decimated, flipped, coarse, wrong units?)
  /// CT: the volume's sample lattice (what was scanned; caps where the skull leaves it); mesh: unbounded.
  ScanFieldOfView field_of_view;
};

/// True when `path` names a volume forensim reads (a folder, .nrrd, .nhdr, .mhd, .mha, .dcm, .tif, .tiff or a
/// file with DICOM's "DICM" marker); false for anything else (taken as a mesh).
bool is_volume_path(const std::filesystem::path& path);

/// A skull from a mesh already in memory (mm): components selected, orientation checked (a closed mesh with
/// negative enclosed volume is turned outward), decimated above options.max_triangles, normals recomputed.
/// Throws InputError naming `source` when the mesh has no triangles.
Skull skull_from_mesh(TriMesh mesh, const std::string& source, const SkullInputOptions& options = {});

/// The bone surface of a CT: the iso-surface at options.bone_iso_value when given; else the iso-surface at 126 HU
/// (1150 for HU + 1024 storage), which finds the bone, and then, with options.half_maximum_height, that surface
/// moved along its normals to the bone's edge: where the bone reaches above the half-maximum height threshold
/// measured across it, to the threshold; thinner bone to the plate model's edge, which keeps it (an iso-surface at the
/// threshold would lose it). Kept at 126 HU when fewer than 200 plateau profiles are found. Closed, outward, welded;
/// not yet reduced to the skull's components. Throws InputError naming `source` for an invalid volume, a non-finite
/// iso-value, or when no voxel lies above the iso-value.
struct BoneSurface {
  TriMesh surface;
  double iso_value = 0.0;                ///< iso-value of `surface`, or the threshold it moved to (stored units)
  std::optional<double> seed_iso_value;  ///< the 126 HU iso-value the threshold was measured from, when measured
  std::size_t threshold_profiles = 0;    ///< plateau profiles averaged into the threshold
  std::vector<std::string> notes;        ///< which iso-value and why
};
BoneSurface extract_bone_surface(const ScalarGrid& volume, const std::string& source,
                                 const SkullInputOptions& options = {});

/// A skull from a CT volume: the bone iso-surface (src/volume, closed and outward) at the given iso-value, or at 126 HU
/// moved to the bone's edge (extract_bone_surface), then as skull_from_mesh.
/// Throws InputError when no voxel lies above the iso-value.
Skull skull_from_volume(const ScalarGrid& volume, const std::string& source, const SkullInputOptions& options = {});

/// A skull from a file: volumes (is_volume_path) through read_volume and skull_from_volume, anything else through
/// import_mesh (with options.mesh_units) and skull_from_mesh. Throws IoError / InputError from the readers.
Skull load_skull(const std::filesystem::path& path, const SkullInputOptions& options = {});

}  // namespace forensim
