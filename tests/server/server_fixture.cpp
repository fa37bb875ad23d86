#include "server/server_fixture.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "core/base64.hpp"
#include "core/run_folder.hpp"
#include "forensim/mummify_job.hpp"
#include "server/skull_templates.hpp"
#include "tet_io/pvd_writer.hpp"
#include "tet_io/vtu_writer.hpp"

namespace forensim::test {

void write_cube_desiccation_run(const std::filesystem::path& folder) {
  TetMesh mesh;
  for (int i = 0; i < 8; ++i) mesh.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // Kuhn's six tets along the diagonal 0-7.
  const int paths[6][2] = {{1, 3}, {1, 5}, {2, 3}, {2, 6}, {4, 5}, {4, 6}};
  for (const auto& p : paths) {
    Tet t{0, p[0], p[1], 7};
    const Vec3 &a = mesh.positions[0], &b = mesh.positions[static_cast<std::size_t>(t[1])],
               &c = mesh.positions[static_cast<std::size_t>(t[2])], &d = mesh.positions[7];
    if ((b - a).dot((c - a).cross(d - a)) < 0) std::swap(t[1], t[2]);
    mesh.tets.push_back(t);
  }
  std::vector<double> water(8);
  std::vector<Vec3> displacement(8);
  for (std::size_t i = 0; i < 8; ++i) {
    water[i] = 10.0 * mesh.positions[i].x();
    displacement[i] = Vec3(0.1 * mesh.positions[i].x(), 0, 0);
  }
  RunFolder run(folder, "mummify");
  // The skin: the cube's boundary as triangles over the same 8 points, shrinking by 0.1 x per frame.
  TriMesh skin;
  skin.positions = mesh.positions;
  skin.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                    {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  PvdSeries skin_series(run.file("skin.pvd"));
  for (int frame = 0; frame < 2; ++frame) {
    TriMesh m = skin;
    std::vector<double> moisture(8), uncertainty(8);
    std::vector<Vec3> colour(8);
    for (std::size_t i = 0; i < 8; ++i) {
      m.positions[i].x() *= 1.0 - 0.1 * frame;
      moisture[i] = 1.0 - 0.25 * frame * mesh.positions[i].x();
      uncertainty[i] = 0.5 + mesh.positions[i].z();
      colour[i] = Vec3(0.5, 0.25 * (1 + frame), 0.125);
    }
    m.vertex_fields.scalars["moisture_ratio"] = moisture;
    m.vertex_fields.scalars["uncertainty"] = uncertainty;
    m.vertex_fields.vectors["colour"] = colour;
    const std::string name = "skin/frame_000" + std::to_string(frame) + ".vtu";
    write_vtu(run.file(name), m);
    run.add_output(name);
    skin_series.add(frame * 2.0, name);
  }
  run.add_output("skin.pvd");
  PvdSeries series(run.file("desiccation.pvd"));
  for (int frame = 0; frame < 2; ++frame) {
    TetMesh m = mesh;
    m.vertex_fields.scalars["water_percent"] = water;
    m.vertex_fields.vectors["displacement"] = displacement;
    for (std::size_t i = 0; i < 8; ++i) m.positions[i] += displacement[i];
    const std::string name = "volume/frame_000" + std::to_string(frame) + ".vtu";
    VtuOptions options;
    options.compress = true;
    write_vtu(run.file(name), m, options);
    run.add_output(name);
    series.add(frame * 2.0, name);
  }
  run.add_output("desiccation.pvd");
  run.write_record();
}

std::shared_ptr<SkullTemplates> shared_skull_templates() {
  static const auto templates = std::make_shared<SkullTemplates>();
  return templates;
}

TestServer::TestServer(const std::filesystem::path& served, std::size_t max_body_bytes, int max_jobs,
                       int max_skull_sessions) {
  ServerOptions options;
  options.port = 0;
  options.served_dir = served;
  options.web_dir = FORENSIM_WEB_DIR;
  options.executable = FORENSIM_CLI_PATH;
  options.max_body_bytes = max_body_bytes;
  options.max_running_jobs = max_jobs;
  options.max_skull_sessions = max_skull_sessions;
  options.skull_templates = shared_skull_templates();
  server = std::make_unique<ApiServer>(options);
  server->jobs().add_kind(cli::mummify_job_kind());
  port = server->start();
}

TestServer::~TestServer() {
  server->stop();
}

httplib::Client TestServer::client() const {
  httplib::Client c("127.0.0.1", port);
  c.set_read_timeout(60, 0);
  return c;
}

nlohmann::json TestServer::wait_job(const std::string& id, double seconds) const {
  auto c = client();
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  nlohmann::json j;
  while (std::chrono::steady_clock::now() < end) {
    j = body_json(c.Get(("/api/jobs/" + id).c_str()));
    if (j.is_object() && j.value("state", "") != "running") return j;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return j;
}

nlohmann::json body_json(const httplib::Result& r) {
  if (!r) return nullptr;
  return nlohmann::json::parse(r->body, nullptr, false);
}

std::vector<float> floats(const std::string& b64) {
  std::size_t bad = 0;
  const auto bytes = base64_decode(b64, bad);
  EXPECT_TRUE(bytes.has_value());
  if (!bytes) return {};
  std::vector<float> out(bytes->size() / sizeof(float));
  std::memcpy(out.data(), bytes->data(), out.size() * sizeof(float));
  return out;
}

}  // namespace forensim::test
