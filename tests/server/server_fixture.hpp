#pragma once
// A served folder for the API tests with a small desiccation run written the way `forensim mummify` writes
// one (run.json, a .pvd series of .vtu frames), and a server on a free loopback port in this process.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "server/api_server.hpp"

// <resolv.h>, which httplib.h includes, defines the macro _res (glibc's resolver state, unused here), a
// variable name in Eigen's headers that the tests include after this one.
#include <httplib.h>
#undef _res

namespace forensim::test {

/// Unit cube (mm) in six positively oriented tets, with node fields "water_percent" (= 10 x) and
/// "displacement" (= (0.1 x, 0, 0)), written as frames 0 and 1 of a mummify-like run in `folder`; beside it a skin
/// series (skin.pvd): the cube's 12 boundary triangles over the same 8 points, x scaled by 0.9 in frame 1, with
/// "moisture_ratio" (1 - 0.25 frame x), "uncertainty" (0.5 + z) and "colour" ((0.5, 0.25 (1 + frame), 0.125)).
void write_cube_desiccation_run(const std::filesystem::path& folder);

/// One set of the skull editor's template heads for every server of the test program (each built once).
std::shared_ptr<SkullTemplates> shared_skull_templates();

/// A server over `served` with the wound and mummify job kinds; started on a free port.
struct TestServer {
  explicit TestServer(const std::filesystem::path& served, std::size_t max_body_bytes = 65536, int max_jobs = 2,
                      int max_skull_sessions = 4);
  ~TestServer();
  httplib::Client client() const;
  /// Waits until the job ends (polling GET /api/jobs/ID); returns its last description.
  nlohmann::json wait_job(const std::string& id, double seconds = 120.0) const;
  std::unique_ptr<ApiServer> server;
  int port = 0;
};

/// The JSON body of a response (null when it is not JSON).
nlohmann::json body_json(const httplib::Result& r);
/// The float32 array a base64 string of the API holds (positions_f32 and the like); a bad string fails the test.
std::vector<float> floats(const std::string& b64);

}  // namespace forensim::test
