// forensim serve's API through HTTP: a server in this process on a free loopback port, a served folder with
// a desiccation run, and wound and mummify jobs run by the forensim executable. Every endpoint's success and
// failure, bad JSON, oversize bodies, path traversal, the job limit and loopback-only binding.

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <thread>
#include <vector>

#include "core/atomic_file.hpp"
#include "server/server_fixture.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::body_json;
namespace fs = std::filesystem;

namespace {

// The error object of a JSON error response, checked for its shape.
nlohmann::json error_of(const httplib::Result& r, int status) {
  EXPECT_TRUE(r);
  if (!r) return nullptr;
  EXPECT_EQ(r->status, status) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/json") << r->body;
  const nlohmann::json j = body_json(r);
  EXPECT_TRUE(j.is_object() && j.contains("error")) << r->body;
  if (!j.is_object() || !j.contains("error")) return nullptr;
  EXPECT_EQ(j["error"]["status"], status);
  EXPECT_FALSE(j["error"]["message"].get<std::string>().empty());
  return j["error"];
}

httplib::Result post_json(httplib::Client& c, const std::string& path, const nlohmann::json& body) {
  return c.Post(path.c_str(), body.dump(), "application/json");
}

// A small wound job on the built-in cylinder: one UV stroke, quick to run.
nlohmann::json wound_request(const std::string& output) {
  return {{"kind", "wound"},
          {"output", output},
          {"mesh", "cylinder"},
          {"resolution", 64},
          {"times", "36h"},
          {"job", {{"type", "abrasion"}, {"strokes", {{{"uv", {{0.4, 0.5}, {0.5, 0.55}}}, {"radius_mm", 4}}}}}}};
}

class Api : public ::testing::Test {
 protected:
  void SetUp() override {
    served = test::scratch_dir(std::string("api_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    test::write_cube_desiccation_run(served / "dry");
    outside = served.parent_path() / (served.filename().string() + "_outside");
    fs::create_directories(outside);
    std::ofstream(outside / "secret.txt") << "secret";
  }
  fs::path served, outside;
};

}  // namespace

TEST_F(Api, HealthListsKindsAndLimits) {
  test::TestServer s(served);
  auto c = s.client();
  const auto r = c.Get("/api/health");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  const auto j = body_json(r);
  EXPECT_EQ(j["job_kinds"], nlohmann::json::array({"mummify", "wound"}));
  EXPECT_EQ(j["limits"]["max_body_bytes"], 65536);
  EXPECT_FALSE(j["forensim_version"].get<std::string>().empty());
}

TEST_F(Api, DefaultsToLoopbackOnly) {
  EXPECT_EQ(ServerOptions{}.host, "127.0.0.1");
  test::TestServer s(served);
  // Any non-loopback IPv4 address of this machine must not reach the server.
  ifaddrs* list = nullptr;
  ASSERT_EQ(getifaddrs(&list), 0);
  std::string address;
  for (ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr || a->ifa_addr->sa_family != AF_INET) continue;
    char text[INET_ADDRSTRLEN];
    inet_ntop(AF_INET, &reinterpret_cast<sockaddr_in*>(a->ifa_addr)->sin_addr, text, sizeof text);
    if (std::string(text).rfind("127.", 0) != 0) {
      address = text;
      break;
    }
  }
  freeifaddrs(list);
  auto local = s.client();
  EXPECT_TRUE(local.Get("/api/health"));
  if (address.empty()) GTEST_SKIP() << "this machine has no non-loopback IPv4 address to try";
  httplib::Client remote(address, s.port);
  remote.set_connection_timeout(2, 0);
  EXPECT_FALSE(remote.Get("/api/health")) << "reachable through " << address;
}

TEST_F(Api, ListsRunsAndDescribesOne) {
  fs::create_directories(served / "broken");
  std::ofstream(served / "broken" / "run.json") << "{not json";
  test::TestServer s(served);
  auto c = s.client();
  const auto runs = body_json(c.Get("/api/runs"));
  ASSERT_EQ(runs["runs"].size(), 1u) << runs.dump();
  EXPECT_EQ(runs["runs"][0]["path"], "dry");
  EXPECT_EQ(runs["runs"][0]["command"], "mummify");
  ASSERT_EQ(runs["skipped"].size(), 1u);
  EXPECT_EQ(runs["skipped"][0]["path"], "broken");

  const auto run = body_json(c.Get("/api/run?path=dry"));
  EXPECT_EQ(run["kind"], "mummify");
  ASSERT_EQ(run["frames"].size(), 2u);
  EXPECT_EQ(run["frames"][1]["time_days"], 2.0);
  EXPECT_EQ(run["frames"][1]["file"], "volume/frame_0001.vtu");
  ASSERT_EQ(run["skin_frames"].size(), 2u);
  EXPECT_EQ(run["skin_frames"][1]["time_days"], 2.0);
  EXPECT_EQ(run["skin_frames"][1]["file"], "skin/frame_0001.vtu");
  std::set<std::string> files;
  for (const auto& f : run["files"]) files.insert(f["path"].get<std::string>());
  EXPECT_TRUE(files.count("run.json") && files.count("desiccation.pvd") && files.count("volume/frame_0000.vtu"));

  EXPECT_EQ(error_of(c.Get("/api/run?path=nothing"), 404)["field"], "path");
  error_of(c.Get("/api/run?path=dry/volume"), 404);  // a folder without run.json
  error_of(c.Get("/api/run?path=broken"), 400);      // malformed run.json
  EXPECT_EQ(error_of(c.Get("/api/run?path=../"), 400)["field"], "path");
}

TEST_F(Api, ServesFilesOnlyInsideTheServedFolder) {
  fs::create_symlink(outside, served / "out_link");
  fs::create_symlink(served / "dry", served / "in_link");
  test::TestServer s(served);
  auto c = s.client();
  const auto ok = c.Get("/api/files/dry/run.json");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  EXPECT_EQ(ok->get_header_value("Content-Type"), "application/json");
  EXPECT_EQ(ok->body, read_file(served / "dry" / "run.json"));
  EXPECT_EQ(c.Get("/api/files/in_link/run.json")->status, 200);

  const std::string secret_name = outside.filename().string() + "/secret.txt";
  for (const std::string& bad :
       std::vector<std::string>{"/api/files/../" + secret_name, "/api/files/dry/../../" + secret_name,
                                "/api/files/%2e%2e/" + secret_name, "/api/files/..%2f" + secret_name,
                                "/api/files//etc/passwd", "/api/files/%2fetc%2fpasswd", "/api/files/dry%00/run.json"}) {
    const auto r = c.Get(bad.c_str());
    ASSERT_TRUE(r) << bad;
    EXPECT_EQ(r->status, 400) << bad << ": " << r->body;
    EXPECT_EQ(r->body.find("secret\""), std::string::npos);
  }
  error_of(c.Get("/api/files/out_link/secret.txt"), 403);
  error_of(c.Get("/api/files/dry/none.png"), 404);
  error_of(c.Get("/api/files/dry/volume"), 404);
  // The web folder has the same guard.
  EXPECT_EQ(c.Get("/../CMakeLists.txt")->status, 400);
  const auto index = c.Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_EQ(index->get_header_value("Content-Type"), "text/html; charset=utf-8");
  error_of(c.Get("/no-such-page.html"), 404);
  error_of(c.Get("/api/no-such-endpoint"), 404);
}

TEST_F(Api, FrameIsTheBoundaryWithFields) {
  test::TestServer s(served);
  auto c = s.client();
  const auto f = body_json(c.Get("/api/frame?path=dry/volume/frame_0001.vtu"));
  ASSERT_TRUE(f.is_object());
  ASSERT_EQ(f["vertex_count"], 8);
  EXPECT_EQ(f["triangle_count"], 12);  // two per cube face
  const auto& p = f["positions"];
  const auto& rest = f["rest_positions"];
  const auto& water = f["scalars"]["water_percent"];
  for (std::size_t v = 0; v < 8; ++v) {
    const double x0 = rest[3 * v].get<double>();
    EXPECT_NEAR(p[3 * v].get<double>(), 1.1 * x0, 1e-3);  // displaced by 0.1 x
    EXPECT_NEAR(water[v].get<double>(), 10.0 * x0, 1e-3);
  }
  EXPECT_NEAR(f["ranges"]["water_percent"][1].get<double>(), 10.0, 1e-9);
  EXPECT_EQ(f["cells"], "tetrahedra");
  EXPECT_FALSE(f["vectors"].contains("displacement"));  // served as rest_positions
  EXPECT_EQ(error_of(c.Get("/api/frame"), 400)["field"], "path");
  error_of(c.Get("/api/frame?path=dry/run.json"), 400);
  error_of(c.Get("/api/frame?path=dry/volume/none.vtu"), 404);
  std::ofstream(served / "dry" / "bad.vtu") << "<VTKFile>";
  error_of(c.Get("/api/frame?path=dry/bad.vtu"), 400);
}

TEST_F(Api, FrameOfATriangleSkinKeepsItsVerticesAndFields) {
  test::TestServer s(served);
  auto c = s.client();
  const auto f = body_json(c.Get("/api/frame?path=dry/skin/frame_0001.vtu"));
  ASSERT_TRUE(f.is_object());
  EXPECT_EQ(f["cells"], "triangles");
  ASSERT_EQ(f["vertex_count"], 8);
  ASSERT_EQ(f["triangle_count"], 12);
  EXPECT_FALSE(f.contains("rest_positions"));  // no displacement: the viewer measures against the first frame
  EXPECT_EQ(f["triangles"][6], 4);             // the file's order is kept
  EXPECT_EQ(f["triangles"][8], 7);
  for (std::size_t v = 0; v < 8; ++v) {
    const double x = (v & 1) ? 1.0 : 0.0, z = (v & 4) ? 1.0 : 0.0;
    EXPECT_NEAR(f["positions"][3 * v].get<double>(), 0.9 * x, 1e-9);
    EXPECT_NEAR(f["scalars"]["moisture_ratio"][v].get<double>(), 1.0 - 0.25 * x, 1e-9);
    EXPECT_NEAR(f["scalars"]["uncertainty"][v].get<double>(), 0.5 + z, 1e-9);
    EXPECT_NEAR(f["vectors"]["colour"][3 * v + 1].get<double>(), 0.5, 1e-9);
  }
  EXPECT_NEAR(f["ranges"]["uncertainty"][0].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(f["ranges"]["uncertainty"][1].get<double>(), 1.5, 1e-9);
  // A malformed triangle file is reported by the triangle reader (its cells were not tets).
  std::string text = read_file(served / "dry" / "skin" / "frame_0000.vtu");
  const std::string key = "Name=\"connectivity\"";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, key.size(), "Name=\"connections\"");
  std::ofstream(served / "dry" / "skin_bad.vtu") << text;
  const auto e = error_of(c.Get("/api/frame?path=dry/skin_bad.vtu"), 400);
  ASSERT_TRUE(e.is_object());
  EXPECT_NE(e["message"].get<std::string>().find("connectivity"), std::string::npos) << e.dump();
}

TEST_F(Api, BuiltinMeshAsGlb) {
  test::TestServer s(served);
  auto c = s.client();
  const auto r = c.Get("/api/meshes/cylinder.glb");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->get_header_value("Content-Type"), "model/gltf-binary");
  ASSERT_GT(r->body.size(), 12u);
  EXPECT_EQ(r->body.substr(0, 4), "glTF");
  error_of(c.Get("/api/meshes/skull.glb"), 404);
  EXPECT_EQ(body_json(c.Get("/api/meshes"))["meshes"].size(), 2u);
}

TEST_F(Api, BadRequestsNameTheFieldAtFault) {
  test::TestServer s(served);
  auto c = s.client();
  error_of(c.Post("/api/jobs", "{\"kind\": ", "application/json"), 400);
  error_of(c.Post("/api/jobs", "[1, 2]", "application/json"), 400);
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", {{"output", "x"}}), 400)["field"], "/kind");
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", {{"kind", "reconstruct"}}), 400)["field"], "/kind");
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", {{"kind", 3}}), 400)["field"], "/kind");
  for (const std::string& bad : std::vector<std::string>{"../escape", "a/b", ".hidden", "", std::string(65, 'a')}) {
    EXPECT_EQ(error_of(post_json(c, "/api/jobs", {{"kind", "wound"}, {"output", bad}}), 400)["field"], "/output")
        << bad;
  }
  auto request = wound_request("w");
  request["colour"] = "red";
  const auto unknown = error_of(post_json(c, "/api/jobs", request), 400);
  EXPECT_EQ(unknown["field"], "/colour");
  request = wound_request("w");
  request["job"]["strokes"][0]["raduis_mm"] = 2;
  const auto typo = error_of(post_json(c, "/api/jobs", request), 400);
  EXPECT_EQ(typo["field"], "/job/strokes/0/raduis_mm");
  EXPECT_NE(typo["message"].get<std::string>().find("radius_mm"), std::string::npos);  // did you mean
  request = wound_request("w");
  request["job"]["strokes"][0]["radius_mm"] = -1;
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", request), 400)["field"], "/job/strokes/0/radius_mm");
  request = wound_request("w");
  request["job"]["strokes"][0]["uv"] = {{1.5, 0.5}};
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", request), 400)["field"], "/job/strokes/0/uv");
  request = wound_request("w");
  request["resolution"] = 100000;
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", request), 400)["field"], "/resolution");
  request = wound_request("w");
  request["times"] = "36 fortnights";
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", request), 400)["field"], "/times");
  request = wound_request("w");
  request["mesh"] = "../" + outside.filename().string() + "/secret.txt";
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", request), 400)["field"], "/mesh");
  request["mesh"] = "dry/run.json";
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", request), 400)["field"], "/mesh");
  const nlohmann::json mummify = {{"kind", "mummify"}, {"output", "m"}, {"job", {{"days", 0}}}};
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", mummify), 400)["field"], "/job/days");
  const nlohmann::json typo_env = {{"kind", "mummify"}, {"job", {{"enviroment", {{"humidity_percent", 20}}}}}};
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", typo_env), 400)["field"], "/job/enviroment");
  const nlohmann::json model_out = {{"kind", "mummify"}, {"job", {{"body", {{"model", "../"}}}}}};
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", model_out), 400)["field"], "/job/body/model");
  // Nothing was written for any refused request, and no job exists.
  EXPECT_FALSE(fs::exists(served / "w"));
  EXPECT_FALSE(fs::exists(served / "m"));
  EXPECT_TRUE(body_json(c.Get("/api/jobs"))["jobs"].empty());
  EXPECT_EQ(error_of(post_json(c, "/api/jobs", {{"kind", "wound"}, {"output", "dry"}}), 409)["field"], "/output");
}

TEST_F(Api, OversizeBodyIs413) {
  test::TestServer s(served, 4096);
  auto c = s.client();
  nlohmann::json big = wound_request("big");
  big["job"]["strokes"][0]["uv"] = nlohmann::json::array();
  for (int i = 0; i < 1000; ++i) big["job"]["strokes"][0]["uv"].push_back({0.4 + 1e-4 * i, 0.5});
  ASSERT_GT(big.dump().size(), 4096u);
  error_of(post_json(c, "/api/jobs", big), 413);
  EXPECT_FALSE(fs::exists(served / "big"));
  // Just under the limit is read (and refused for its content, not its size).
  const std::string small =
      "{\"kind\": \"wound\", \"mesh\": \"cylinder\", \"pad\": \"" + std::string(3000, 'x') + "\"}";
  EXPECT_EQ(error_of(c.Post("/api/jobs", small, "application/json"), 400)["field"], "/pad");
}

TEST_F(Api, WoundJobRunsAndItsRunIsServed) {
  test::TestServer s(served);
  auto c = s.client();
  const auto started = c.Post("/api/jobs", wound_request("wound1").dump(), "application/json");
  ASSERT_TRUE(started);
  ASSERT_EQ(started->status, 202) << started->body;
  const auto job = body_json(started);
  EXPECT_EQ(job["kind"], "wound");
  EXPECT_EQ(job["output"], "wound1");
  const auto done = s.wait_job(job["id"]);
  ASSERT_EQ(done["state"], "succeeded") << done.dump(2);
  EXPECT_EQ(done["exit_code"], 0);
  EXPECT_EQ(done["progress"]["fraction"], 1.0);
  EXPECT_EQ(error_of(c.Post(("/api/jobs/" + job["id"].get<std::string>() + "/cancel").c_str(), "", "text/plain"), 409)
                .is_object(),
            true);

  const auto run = body_json(c.Get("/api/run?path=wound1"));
  EXPECT_EQ(run["kind"], "wound");
  ASSERT_TRUE(run.contains("timeline"));
  EXPECT_EQ(run["timeline"]["type"], "abrasion");
  EXPECT_EQ(run["timeline"]["texture_size"], nlohmann::json::array({64, 64}));
  const std::string first_key = run["timeline"]["key_files"][0];
  const auto png = c.Get(("/api/files/wound1/maps/" + first_key + "_color.png").c_str());
  ASSERT_TRUE(png);
  EXPECT_EQ(png->status, 200);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  EXPECT_EQ(png->body.substr(1, 3), "PNG");
  // The job file the run read is the request's "job", and the run is listed.
  EXPECT_EQ(nlohmann::json::parse(read_file(served / "wound1" / "job.json")), wound_request("wound1")["job"]);
  bool listed = false;
  const auto runs = body_json(c.Get("/api/runs"));
  for (const auto& r : runs["runs"]) listed |= r["path"] == "wound1";
  EXPECT_TRUE(listed);
  EXPECT_EQ(body_json(c.Get("/api/jobs"))["jobs"].size(), 1u);
  error_of(c.Get("/api/jobs/job-999"), 404);
  error_of(c.Post("/api/jobs/job-999/cancel", "", "text/plain"), 404);
}

TEST_F(Api, JobLimitCancelAndEvents) {
  test::TestServer s(served, 65536, 1);
  auto c = s.client();
  // A long mummify run holds the only slot.
  const nlohmann::json long_run = {{"kind", "mummify"}, {"output", "long"}, {"job", {{"days", 3000}}}};
  const auto first = c.Post("/api/jobs", long_run.dump(), "application/json");
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 202) << first->body;
  const std::string id = body_json(first)["id"];
  error_of(post_json(c, "/api/jobs", wound_request("second")), 429);
  EXPECT_FALSE(fs::exists(served / "second"));
  EXPECT_EQ(body_json(c.Get("/api/health"))["running_jobs"], 1);

  // Server-sent events follow the job to its end.
  std::string events;
  std::thread listener([&] {
    auto l = s.client();
    l.Get(("/api/jobs/" + id + "/events").c_str(), [&](const char* data, std::size_t n) {
      events.append(data, n);
      return true;
    });
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto cancelled = c.Post(("/api/jobs/" + id + "/cancel").c_str(), "", "text/plain");
  ASSERT_TRUE(cancelled);
  EXPECT_EQ(cancelled->status, 200);
  const auto end = s.wait_job(id, 30.0);
  EXPECT_EQ(end["state"], "cancelled");
  listener.join();
  EXPECT_EQ(events.rfind("data: ", 0), 0u) << events;
  EXPECT_NE(events.find("\"state\":\"running\""), std::string::npos);
  EXPECT_NE(events.find("\"state\":\"cancelled\""), std::string::npos);
  error_of(c.Get("/api/jobs/job-999/events"), 404);
  // The slot is free again.
  const auto again = post_json(c, "/api/jobs", wound_request("second"));
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 202) << again->body;
  EXPECT_EQ(s.wait_job(body_json(again)["id"])["state"], "succeeded");
}
