#include "server/wound_job_kind.hpp"

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "mesh_io/mesh_import.hpp"
#include "server/api_error.hpp"
#include "server/served_path.hpp"
#include "wound/duration.hpp"
#include "wound/wound_job.hpp"

namespace forensim {

JobKind wound_job_kind(std::shared_ptr<BuiltinMeshes> meshes) {
  JobKind kind;
  kind.name = "wound";
  kind.prepare = [meshes](const JobNode& request, const JobContext& context) {
    PreparedJob out;
    const std::string mesh_name = request.get<std::string>("mesh", "forearm-uv");
    const std::string unit = request.get_choice("unit", "auto", {"auto", "m", "cm", "mm", "in"});
    const long long resolution = request.get_integer("resolution", 512, 32, 4096);
    const long long seed = request.get_integer("seed", 1, 0, 9007199254740991LL);
    const std::string times = request.get<std::string>("times", "1h,36h,5d,3w");
    const long long picture_size = request.get_integer("picture_size", 0, 0, 1024);
    try {
      if (!times.empty()) parse_durations(times, "times");
    } catch (const InputError& e) {
      throw ApiError(400, e.what(), "/times");
    }
    std::vector<std::string> mesh_arguments;
    const TriMesh* mesh = nullptr;
    TriMesh file_mesh;
    if (BuiltinMeshes::known(mesh_name)) {
      mesh = &meshes->mesh(mesh_name);
      mesh_arguments = {"--builtin", mesh_name};
    } else {
      const ServedPath p = resolve_served_path(context.served_root, mesh_name);
      if (p.problem != ServedPathProblem::none) {
        throw ApiError(p.problem == ServedPathProblem::outside ? 403 : 400,
                       p.message + " (a mesh is forearm-uv, cylinder or a file in the served folder)", "/mesh");
      }
      MeshImportOptions options;
      options.unit = unit;
      try {
        file_mesh = import_mesh(p.path, options);
      } catch (const Error& e) {
        throw ApiError(400, e.what(), "/mesh");
      }
      if (!file_mesh.has_uvs()) throw ApiError(400, "mesh '" + mesh_name + "' has no texture coordinates", "/mesh");
      mesh = &file_mesh;
      mesh_arguments = {"--mesh", p.path.string(), "--unit", unit};
    }
    std::vector<std::string> job_arguments;
    if (request.has("job")) {
      const WoundJob job = read_wound_job(request.child("job"), *mesh);
      out.summary["type"] = job.type;
      out.summary["strokes"] = job.strokes.size();
      const std::filesystem::path job_file = context.output_folder / "job.json";
      write_file_atomic(job_file, context.request["job"].dump(2) + "\n");
      job_arguments = {"--strokes", job_file.string()};
    }
    out.summary["mesh"] = mesh_name;
    out.summary["resolution"] = resolution;
    out.summary["times"] = times;
    out.arguments = {"wound",
                     "-o",
                     context.output_folder.string(),
                     "--resolution",
                     std::to_string(resolution),
                     "--seed",
                     std::to_string(seed),
                     "--times",
                     times,
                     "--picture-size",
                     std::to_string(picture_size)};
    out.arguments.insert(out.arguments.end(), mesh_arguments.begin(), mesh_arguments.end());
    out.arguments.insert(out.arguments.end(), job_arguments.begin(), job_arguments.end());
    return out;
  };
  return kind;
}

}  // namespace forensim
