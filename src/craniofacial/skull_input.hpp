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
  /// iso-value of VTK's medical examples, also forensim isosurface's); storage is taken as HU + 1024 when the
  /// volume has no value below -100.
  std::optional<double> bone_iso_value;
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
  std::optional<double> iso_value;  ///< CT: the bone iso-value used (stored volume values)
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

/// A skull from a CT volume: the bone iso-surface (src/volume, closed and outward), then as skull_from_mesh.
/// Throws InputError when no voxel lies above the iso-value.
Skull skull_from_volume(const ScalarGrid& volume, const std::string& source, const SkullInputOptions& options = {});

/// A skull from a file: volumes (is_volume_path) through read_volume and skull_from_volume, anything else through
/// import_mesh (with options.mesh_units) and skull_from_mesh. Throws IoError / InputError from the readers.
Skull load_skull(const std::filesystem::path& path, const SkullInputOptions& options = {});

}  // namespace forensim
