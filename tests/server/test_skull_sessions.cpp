// The skull editor's sessions through HTTP (src/server/skull_sessions.*, skull_session.*): a session on the
// built-in skull of the coarse template, a landmark moved (the face changes, and equals a fresh session from
// the exported landmarks), a landmark added back, depths, guides, expressions, exports and saving; every
// endpoint's failures (bad JSON, unknown session 404, unknown landmark 400, non-finite and far positions,
// traversal in the skull, table and landmark paths, oversize bodies 413, the session limit 429, idle expiry)
// and concurrent edits of one session.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "core/base64.hpp"
#include "craniofacial/landmark_io.hpp"
#include "craniofacial/reconstruction.hpp"
#include "craniofacial/template_landmark_detection.hpp"
#include "server/server_fixture.hpp"
#include "server/skull_session.hpp"
#include "server/skull_templates.hpp"
#include "support/test_support.hpp"

using namespace forensim;
using test::body_json;
using test::floats;
namespace fs = std::filesystem;

namespace {

nlohmann::json error_of(const httplib::Result& r, int status) {
  EXPECT_TRUE(r);
  if (!r) return nullptr;
  EXPECT_EQ(r->status, status) << r->body.substr(0, 400);
  const nlohmann::json j = body_json(r);
  EXPECT_TRUE(j.is_object() && j.contains("error")) << r->body.substr(0, 400);
  if (!j.is_object() || !j.contains("error")) return nullptr;
  EXPECT_EQ(j["error"]["status"], status);
  EXPECT_FALSE(j["error"]["message"].get<std::string>().empty());
  return j["error"];
}

httplib::Result post(httplib::Client& c, const std::string& path, const nlohmann::json& body) {
  return c.Post(path.c_str(), body.dump(), "application/json");
}

nlohmann::json ok(const httplib::Result& r, int status = 200) {
  EXPECT_TRUE(r);
  if (!r) return nullptr;
  EXPECT_EQ(r->status, status) << r->body.substr(0, 600);
  return body_json(r);
}

// A session on the built-in skull with the coarse template and its own landmarks (quick: no detection).
nlohmann::json quick_session(const std::string& landmarks = "template") {
  return {{"template_detail", "coarse"}, {"landmarks", landmarks}};
}

double largest_difference(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, std::abs(double(a[i]) - b[i]));
  return worst;
}

nlohmann::json landmark(const nlohmann::json& list, const std::string& name) {
  for (const auto& l : list)
    if (l["name"] == name) return l;
  return nullptr;
}

std::string session_path(const nlohmann::json& s, const std::string& rest = "") {
  return "/api/skull/sessions/" + s["id"].get<std::string>() + rest;
}

class SkullApi : public ::testing::Test {
 protected:
  void SetUp() override {
    served = test::scratch_dir(std::string("skull_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    outside = served.parent_path() / (served.filename().string() + "_outside");
    fs::create_directories(outside);
    std::ofstream(outside / "skull.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  }
  fs::path served, outside;
};

}  // namespace

TEST_F(SkullApi, CreatesDescribesListsAndDeletesASession) {
  test::TestServer s(served);
  auto c = s.client();
  const auto j = ok(post(c, "/api/skull/sessions", quick_session()), 201);
  ASSERT_TRUE(j.is_object());
  ASSERT_GE(j["landmarks"].size(), 20u);
  for (const auto& l : j["landmarks"]) {
    EXPECT_TRUE(l.contains("name") && l.contains("position_mm") && l.contains("source")) << l.dump();
    EXPECT_GE(l["confidence"].get<double>(), 0.0);
    EXPECT_LE(l["confidence"].get<double>(), 1.0);
  }
  // The face's arrays hold what their counts say.
  const std::size_t vertices = j["face"]["vertex_count"];
  EXPECT_EQ(floats(j["face"]["positions_f32"]).size(), 3 * vertices);
  std::size_t bad = 0;
  EXPECT_EQ(base64_decode(j["face"]["triangles_u32"].get<std::string>(), bad)->size(),
            12 * j["face"]["triangle_count"].get<std::size_t>());
  EXPECT_EQ(floats(j["skull_mesh"]["positions_f32"]).size(), 3 * j["skull_mesh"]["vertex_count"].get<std::size_t>());
  EXPECT_FALSE(j["guide_values"].empty());

  const auto described = ok(c.Get(session_path(j, "?geometry=0").c_str()));
  EXPECT_FALSE(described["face"].contains("triangles_u32"));
  EXPECT_EQ(largest_difference(floats(described["face"]["positions_f32"]), floats(j["face"]["positions_f32"])), 0.0);
  const auto list = ok(c.Get("/api/skull/sessions"));
  ASSERT_EQ(list["sessions"].size(), 1u);
  EXPECT_EQ(list["sessions"][0]["id"], j["id"]);
  EXPECT_EQ(list["limits"]["max_sessions"], 4);

  EXPECT_EQ(ok(c.Delete(session_path(j).c_str()))["deleted"], j["id"]);
  EXPECT_EQ(error_of(c.Get(session_path(j).c_str()), 404)["field"], "id");
  error_of(c.Delete(session_path(j).c_str()), 404);
  error_of(post(c, session_path(j, "/landmarks"), {{"name", "g"}, {"position", {0, 0, 0}}}), 404);
}

TEST_F(SkullApi, MovedLandmarkChangesTheFaceAsAFreshSessionFromTheExportedLandmarks) {
  test::TestServer s(served);
  auto c = s.client();
  const auto a = ok(post(c, "/api/skull/sessions", quick_session()), 201);
  ASSERT_TRUE(a.is_object());
  const std::vector<float> before = floats(a["face"]["positions_f32"]);
  const nlohmann::json g = landmark(a["landmarks"], "g");
  ASSERT_TRUE(g.is_object());
  nlohmann::json to = g["skull_mm"];
  to[2] = to[2].get<double>() + 4.0;  // 4 mm up the forehead
  const auto moved = ok(post(c, session_path(a, "/landmarks"), {{"name", "glabella"}, {"position", to}}));
  ASSERT_TRUE(moved.is_object());
  EXPECT_FALSE(moved["added"].get<bool>());
  EXPECT_EQ(moved["landmark"]["name"], "g");
  EXPECT_EQ(moved["landmark"]["source"], "edited");
  EXPECT_EQ(moved["landmark"]["confidence"], 1.0);
  EXPECT_GT(moved["changed_targets"].get<int>(), 0);
  EXPECT_GE(moved["update_ms"].get<double>(), 0.0);
  const std::vector<float> after = floats(moved["face"]["positions_f32"]);
  EXPECT_GT(largest_difference(before, after), 0.5);  // mm

  // The exported landmarks, read by a fresh session, give the same face.
  const auto mrk = c.Get(session_path(a, "/skull_landmarks.mrk.json").c_str());
  ASSERT_TRUE(mrk);
  ASSERT_EQ(mrk->status, 200);
  const LandmarkSet exported = parse_markups_json(mrk->body, "export");
  EXPECT_EQ(exported.size(), a["landmarks"].size());
  EXPECT_EQ(exported.at("g").source, LandmarkSource::edited);
  std::ofstream(served / "edited.mrk.json") << mrk->body;
  const auto b = ok(post(c, "/api/skull/sessions", quick_session("edited.mrk.json")), 201);
  ASSERT_TRUE(b.is_object());
  // Within 0.01 mm (the edit moved the face by more than 0.5 mm): the edited session re-targets its factored warp
  // and its skull/skin correction pairs, the fresh one fits them anew.
  EXPECT_LT(largest_difference(after, floats(b["face"]["positions_f32"])), 1e-2);

  // Without g, then g added back where it was moved to: the same face again.
  LandmarkSet without = exported;
  without.remove("g");
  std::ofstream(served / "without_g.mrk.json") << markups_json_text(without);
  const auto d = ok(post(c, "/api/skull/sessions", quick_session("without_g.mrk.json")), 201);
  ASSERT_TRUE(d.is_object());
  const nlohmann::json addable_g = landmark(d["addable"], "g");
  ASSERT_TRUE(addable_g.is_object()) << d["addable"].dump();
  EXPECT_TRUE(addable_g["moves_face"].get<bool>());
  const auto added = ok(post(c, session_path(d, "/landmarks"), {{"name", "g"}, {"position", to}}));
  EXPECT_TRUE(added["added"].get<bool>());
  EXPECT_EQ(added["landmarks"].size(), a["landmarks"].size());
  EXPECT_LT(largest_difference(after, floats(added["face"]["positions_f32"])), 1e-2);
  // A landmark without a skin pair (porion) is kept for the export and leaves the face alone.
  const auto porion = ok(post(c, session_path(d, "/landmarks"), {{"name", "po_L"}, {"position", g["skull_mm"]}}));
  EXPECT_TRUE(porion["added"].get<bool>());
  EXPECT_EQ(porion["landmarks"].size(), a["landmarks"].size() + 1);
  EXPECT_EQ(largest_difference(floats(porion["face"]["positions_f32"]), floats(added["face"]["positions_f32"])), 0.0);
}

TEST_F(SkullApi, BadEditsAnswer400NamingTheFieldAndLeaveTheSessionAlone) {
  test::TestServer s(served);
  auto c = s.client();
  const auto a = ok(post(c, "/api/skull/sessions", quick_session()), 201);
  ASSERT_TRUE(a.is_object());
  const std::string edit = session_path(a, "/landmarks");
  const nlohmann::json g = landmark(a["landmarks"], "g")["skull_mm"];
  EXPECT_EQ(error_of(post(c, edit, {{"name", "glabela_x"}, {"position", g}}), 400)["field"], "/name");
  EXPECT_EQ(error_of(post(c, edit, {{"name", "se'"}, {"position", g}}), 400)["field"], "/name");  // a skin landmark
  EXPECT_EQ(error_of(post(c, edit, {{"name", ""}, {"position", g}}), 400)["field"], "/name");
  EXPECT_EQ(error_of(post(c, edit, {{"position", g}}), 400)["field"], "/name");
  EXPECT_EQ(error_of(post(c, edit, {{"name", "g"}, {"position", {1, 2}}}), 400)["field"], "/position");
  EXPECT_EQ(error_of(post(c, edit, {{"name", "g"}, {"position", {0, 0, 1e9}}}), 400)["field"], "/position");
  EXPECT_EQ(error_of(post(c, edit, {{"name", "g"}, {"position", {0, "x", 0}}}), 400)["field"], "/position");
  // 60 mm in front of the skull: no closest point within reach.
  nlohmann::json far = g;
  far[1] = far[1].get<double>() - 60.0;
  EXPECT_EQ(error_of(post(c, edit, {{"name", "g"}, {"position", far}}), 400)["field"], "/position");
  EXPECT_EQ(error_of(post(c, edit, {{"name", "g"}, {"position", g}, {"positon", g}}), 400)["field"], "/positon");
  // Not JSON, NaN (not JSON either), an overflowing number, not an object.
  error_of(c.Post(edit.c_str(), "{\"name\": \"g\", ", "application/json"), 400);
  error_of(c.Post(edit.c_str(), "{\"name\": \"g\", \"position\": [NaN, 0, 0]}", "application/json"), 400);
  error_of(c.Post(edit.c_str(), "{\"name\": \"g\", \"position\": [1e999, 0, 0]}", "application/json"), 400);
  error_of(c.Post(edit.c_str(), "[1, 2, 3]", "application/json"), 400);
  // Over the body limit (64 KiB in the tests).
  nlohmann::json big = {{"name", "g"}, {"position", g}, {"pad", std::string(70000, 'x')}};
  error_of(post(c, edit, big), 413);
  // None of it changed the face.
  EXPECT_EQ(largest_difference(floats(ok(c.Get(session_path(a, "?geometry=0").c_str()))["face"]["positions_f32"]),
                               floats(a["face"]["positions_f32"])),
            0.0);
  // Unknown session and endpoint.
  error_of(post(c, "/api/skull/sessions/nope/landmarks", {{"name", "g"}, {"position", g}}), 404);
  error_of(post(c, "/api/skull/sessions/nope/depths", nlohmann::json::object()), 404);
  error_of(c.Get("/api/skull/sessions/nope/head.glb"), 404);
  error_of(c.Get("/api/skull/sessions/nope"), 404);
}

TEST_F(SkullApi, SessionRequestsAreCheckedAndPathsStayInsideTheServedFolder) {
  fs::create_symlink(outside / "skull.obj", served / "linked.obj");
  std::ofstream(served / "garbage.obj") << "this is not a mesh\n";
  std::ofstream(served / "bad.csv") << "landmark,mean_mm\n";
  test::TestServer s(served);
  auto c = s.client();
  const std::string create = "/api/skull/sessions";
  auto field = [&](const nlohmann::json& body, int status) {
    const auto e = error_of(post(c, create, body), status);
    return e.is_object() ? e["field"].get<std::string>() : std::string();
  };
  EXPECT_EQ(field({{"skull", "../" + outside.filename().string() + "/skull.obj"}}, 400), "/skull");
  EXPECT_EQ(field({{"skull", (outside / "skull.obj").string()}}, 400), "/skull");
  EXPECT_EQ(field({{"skull", "linked.obj"}}, 403), "/skull");
  EXPECT_EQ(field({{"skull", "missing.obj"}}, 404), "/skull");
  EXPECT_EQ(field({{"skull", "garbage.obj"}, {"template_detail", "coarse"}}, 400), "/skull");
  EXPECT_EQ(field({{"skull", "garbage.obj"}, {"landmarks", "template"}}, 400), "/landmarks");
  EXPECT_EQ(field({{"landmarks", "../x.mrk.json"}}, 400), "/landmarks");
  EXPECT_EQ(field({{"table", "../x.csv"}}, 400), "/table");
  EXPECT_EQ(field({{"table", "bad.csv"}, {"template_detail", "coarse"}}, 400), "/table");
  EXPECT_EQ(field({{"sex", "unknown"}}, 400), "/sex");
  EXPECT_EQ(field({{"template_detail", "fine"}}, 400), "/template_detail");
  EXPECT_EQ(field({{"skul", "builtin"}}, 400), "/skul");
  EXPECT_EQ(field({{"guides", {{"lateral", {1, 0}}}}}, 400), "/guides/lateral");
  error_of(c.Post(create.c_str(), "not json", "application/json"), 400);
  error_of(post(c, create, {{"skull", std::string(70000, 'a')}}), 413);
  EXPECT_TRUE(ok(c.Get(create.c_str()))["sessions"].empty());
}

TEST_F(SkullApi, DepthsGuidesAndExpressionsChangeTheFace) {
  std::ofstream(served / "table.csv") << "landmark,mean_mm,sex,population,build,source\n";
  test::TestServer s(served);
  auto c = s.client();
  const auto a = ok(post(c, "/api/skull/sessions", quick_session()), 201);
  ASSERT_TRUE(a.is_object());
  const std::vector<float> neutral = floats(a["face"]["positions_f32"]);
  // Obese depths: thicker soft tissue, so the face lies farther from the skull's centre on average.
  auto mean_radius = [](const std::vector<float>& p) {
    double cx = 0, cy = 0, cz = 0, r = 0;
    const std::size_t n = p.size() / 3;
    for (std::size_t i = 0; i < n; ++i) cx += p[3 * i], cy += p[3 * i + 1], cz += p[3 * i + 2];
    cx /= n, cy /= n, cz /= n;
    for (std::size_t i = 0; i < n; ++i) r += std::hypot(p[3 * i] - cx, p[3 * i + 1] - cy, p[3 * i + 2] - cz);
    return r / n;
  };
  const auto obese = ok(post(c, session_path(a, "/depths"), {{"build", "obese"}}));
  ASSERT_TRUE(obese.is_object());
  EXPECT_EQ(obese["depths"]["build"], "obese");
  EXPECT_GT(mean_radius(floats(obese["face"]["positions_f32"])), mean_radius(neutral) + 0.2);
  const auto back = ok(post(c, session_path(a, "/depths"), nlohmann::json::object()));
  EXPECT_LT(largest_difference(neutral, floats(back["face"]["positions_f32"])), 1e-3);
  EXPECT_EQ(error_of(post(c, session_path(a, "/depths"), {{"build", "fat"}}), 400)["field"], "/build");
  EXPECT_EQ(error_of(post(c, session_path(a, "/depths"), {{"table", "../t.csv"}}), 400)["field"], "/table");
  EXPECT_EQ(error_of(post(c, session_path(a, "/depths"), {{"table", "none.csv"}}), 404)["field"], "/table");
  EXPECT_EQ(error_of(post(c, session_path(a, "/depths"), {{"table", "table.csv"}}), 400)["field"], "/table");

  // Guides: the mouth 6 mm wider on the left moves ch'_L there; null takes the second warp away again.
  const double corner = a["guide_values"]["mouth_corner_left_mm"];
  const auto guided = ok(post(c, session_path(a, "/guides"), {{"guides", {{"mouth_corner_left_mm", corner + 6.0}}}}));
  ASSERT_TRUE(guided.is_object());
  EXPECT_NEAR(guided["guide_values"]["mouth_corner_left_mm"].get<double>(), corner + 6.0, 1e-9);
  ASSERT_EQ(guided["guides_adjusted"].size(), 1u);
  EXPECT_EQ(guided["guides_adjusted"][0]["name"], "ch'_L");
  EXPECT_NEAR(guided["guides_adjusted"][0]["to_mm"][0].get<double>(), corner + 6.0, 1e-6);
  EXPECT_GT(largest_difference(neutral, floats(guided["face"]["positions_f32"])), 1.0);
  EXPECT_EQ(error_of(post(c, session_path(a, "/guides"),
                          {{"guides", {{"lateral", {0, 0, 1}}, {"mouth_corner_left_mm", corner}}}}),
                     400)["field"],
            "/guides");  // lateral along up
  EXPECT_EQ(error_of(post(c, session_path(a, "/guides"), {{"guides", 3}}), 400)["field"], "/guides");
  EXPECT_EQ(error_of(post(c, session_path(a, "/guides"), {{"guides", {{"mouth", 1}}}}), 400)["field"], "/guides/mouth");
  // The refused guides left the guided face.
  EXPECT_EQ(largest_difference(floats(ok(c.Get(session_path(a, "?geometry=0").c_str()))["face"]["positions_f32"]),
                               floats(guided["face"]["positions_f32"])),
            0.0);
  const auto unguided = ok(post(c, session_path(a, "/guides"), {{"guides", nullptr}}));
  EXPECT_TRUE(unguided["guides"].is_null());
  EXPECT_LT(largest_difference(neutral, floats(unguided["face"]["positions_f32"])), 1e-3);

  // An expression moves the face (the smile's mouth corners by millimetres); a second request is cached.
  const auto smile = ok(post(c, session_path(a, "/expressions"), {{"name", "smile"}}));
  ASSERT_TRUE(smile.is_object());
  EXPECT_FALSE(smile["cached"].get<bool>());
  EXPECT_GT(smile["max_displacement_mm"].get<double>(), 1.0);
  // The largest coordinate change lies between the largest displacement / sqrt(3) and the displacement itself.
  const double largest = largest_difference(neutral, floats(smile["positions_f32"]));
  EXPECT_LE(largest, smile["max_displacement_mm"].get<double>() + 1e-3);
  EXPECT_GE(largest, smile["max_displacement_mm"].get<double>() / std::sqrt(3.0) - 1e-3);
  const auto again = ok(post(c, session_path(a, "/expressions"), {{"name", "smile"}}));
  EXPECT_TRUE(again["cached"].get<bool>());
  EXPECT_EQ(largest_difference(floats(again["positions_f32"]), floats(smile["positions_f32"])), 0.0);
  const auto neutral_pose = ok(post(c, session_path(a, "/expressions"), {{"name", "neutral"}}));
  EXPECT_LT(neutral_pose["max_displacement_mm"].get<double>(), 0.05);
  EXPECT_EQ(error_of(post(c, session_path(a, "/expressions"), {{"name", "grin"}}), 400)["field"], "/name");
  EXPECT_EQ(error_of(post(c, session_path(a, "/expressions"), nlohmann::json::object()), 400)["field"], "/name");
}

TEST_F(SkullApi, ExportsTheHeadAsGlbAndSavesARunFolder) {
  test::TestServer s(served);
  auto c = s.client();
  const auto a = ok(post(c, "/api/skull/sessions", quick_session()), 201);
  ASSERT_TRUE(a.is_object());
  const auto glb = c.Get(session_path(a, "/head.glb?expressions=smile,frown").c_str());
  ASSERT_TRUE(glb);
  ASSERT_EQ(glb->status, 200);
  ASSERT_GT(glb->body.size(), 20u);
  EXPECT_EQ(glb->body.substr(0, 4), "glTF");
  // The JSON chunk: two meshes (head, skull), the head with the two expressions as morph targets.
  std::uint32_t json_length = 0;
  std::memcpy(&json_length, glb->body.data() + 12, 4);
  const auto gltf = nlohmann::json::parse(glb->body.substr(20, json_length));
  ASSERT_EQ(gltf["meshes"].size(), 2u);
  EXPECT_EQ(gltf["meshes"][0]["primitives"][0]["targets"].size(), 2u);
  EXPECT_EQ(gltf["meshes"][0]["extras"]["targetNames"], nlohmann::json::array({"smile", "frown"}));
  error_of(c.Get(session_path(a, "/head.glb?expressions=smile,,frown").c_str()), 400);
  error_of(c.Get(session_path(a, "/head.glb?expressions=grin").c_str()), 400);
  const auto skin = c.Get(session_path(a, "/skin_landmarks.mrk.json").c_str());
  ASSERT_TRUE(skin);
  LandmarkReadOptions keep;
  keep.naming = LandmarkNaming::keep;
  EXPECT_TRUE(parse_markups_json(skin->body, "skin", keep).contains("se'"));

  const auto saved = ok(post(c, session_path(a, "/save"), {{"output", "edit1"}, {"expressions", {"smile"}}}), 201);
  EXPECT_EQ(saved["output"], "edit1");
  for (const char* f :
       {"head.glb", "skull_landmarks.mrk.json", "skin_landmarks.mrk.json", "provenance.json", "run.json"}) {
    EXPECT_TRUE(fs::is_regular_file(served / "edit1" / f)) << f;
  }
  EXPECT_EQ(read_landmarks(served / "edit1" / "skull_landmarks.mrk.json").size(), a["landmarks"].size());
  EXPECT_EQ(ok(c.Get("/api/run?path=edit1"))["kind"], "reconstruct");
  EXPECT_EQ(error_of(post(c, session_path(a, "/save"), {{"output", "edit1"}}), 409)["field"], "/output");
  EXPECT_EQ(error_of(post(c, session_path(a, "/save"), {{"output", "../edit2"}}), 400)["field"], "/output");
  EXPECT_EQ(error_of(post(c, session_path(a, "/save"), {{"output", "edit2"}, {"expressions", {"grin"}}}), 400)["field"],
            "/expressions");
  EXPECT_FALSE(fs::exists(served / "edit2"));
}

TEST_F(SkullApi, ConcurrentEditsOfOneSessionAreServedOneAfterTheOther) {
  test::TestServer s(served);
  auto c = s.client();
  const auto a = ok(post(c, "/api/skull/sessions", quick_session()), 201);
  ASSERT_TRUE(a.is_object());
  const nlohmann::json g = landmark(a["landmarks"], "g")["skull_mm"];
  // Four clients move g to four heights at once, each several times; every answer is complete.
  std::vector<std::thread> threads;
  std::vector<int> good(4, 0);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      auto client = s.client();
      nlohmann::json to = g;
      to[2] = to[2].get<double>() + 1.0 + t;
      for (int k = 0; k < 3; ++k) {
        const auto r = post(client, session_path(a, "/landmarks"), {{"name", "g"}, {"position", to}});
        const auto j = body_json(r);
        if (r && r->status == 200 &&
            floats(j["face"]["positions_f32"]).size() == 3 * a["face"]["vertex_count"].get<std::size_t>())
          ++good[static_cast<std::size_t>(t)];
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(good, std::vector<int>(4, 3));
  // The state is the last edit's: moving g there once more changes nothing.
  const auto now = ok(c.Get(session_path(a, "?geometry=0").c_str()));
  const auto again = ok(post(c, session_path(a, "/landmarks"),
                             {{"name", "g"}, {"position", landmark(now["landmarks"], "g")["position_mm"]}}));
  EXPECT_LT(largest_difference(floats(now["face"]["positions_f32"]), floats(again["face"]["positions_f32"])), 1e-4);
}

TEST_F(SkullApi, SessionLimitAndIdleExpiry) {
  {
    test::TestServer s(served, 65536, 2, 1);
    auto c = s.client();
    const auto a = ok(post(c, "/api/skull/sessions", quick_session()), 201);
    error_of(post(c, "/api/skull/sessions", quick_session()), 429);
    ok(c.Delete(session_path(a).c_str()));
    ok(post(c, "/api/skull/sessions", quick_session()), 201);
  }
  ServerOptions options;
  options.port = 0;
  options.served_dir = served;
  options.web_dir = FORENSIM_WEB_DIR;
  options.executable = FORENSIM_CLI_PATH;
  // Long enough that the creation's answer (the meshes, slow under the sanitizers) arrives well within it.
  options.skull_session_idle_s = 2.0;
  options.skull_templates = test::shared_skull_templates();
  ApiServer server(options);
  httplib::Client c("127.0.0.1", server.start());
  c.set_read_timeout(60, 0);
  const auto a = ok(post(c, "/api/skull/sessions", quick_session()), 201);
  ASSERT_TRUE(a.is_object());
  ok(c.Get(session_path(a, "?geometry=0").c_str()));
  std::this_thread::sleep_for(std::chrono::milliseconds(4500));
  error_of(c.Get(session_path(a).c_str()), 404);
  EXPECT_TRUE(ok(c.Get("/api/skull/sessions"))["sessions"].empty());
  server.stop();
}

namespace {

// The violation counts of a reconstruction made directly (not through a session) from the template's own
// landmarks (without `removed`), on the built-in skull, with the session's default depths: its
// violations_json(), counted.
nlohmann::json direct_violations(const std::string& removed = "") {
  const auto head = test::shared_skull_templates()->get("coarse");
  LandmarkSet landmarks = template_skull_landmarks(*head);
  if (!removed.empty()) landmarks.remove(removed);
  ReconstructionOptions options;
  options.fit.count_violations = true;
  const Reconstruction r(*head, head->skull, landmarks, select_session_depths(SkullDepthChoice{}), options);
  return r.violations_json();
}

// The session's answer against the direct reconstruction's final face (no guides: with the interpolated pairs).
void expect_counts(const nlohmann::json& j, const nlohmann::json& want) {
  ASSERT_TRUE(j.is_object());
  const nlohmann::json& final_face = want["with_interpolated_landmarks"];
  EXPECT_EQ(j["skull_through_skin"], final_face["skull_outside_skin"]);
  EXPECT_EQ(j["skin_inside_skull"], final_face["skin_inside_skull"]);
  EXPECT_NEAR(j["max_skull_protrusion_mm"].get<double>(), final_face["max_skull_protrusion_mm"].get<double>(), 1e-9);
}

}  // namespace

TEST_F(SkullApi, RemovedLandmarkChangesTheFaceAndViolationsMatchADirectReconstruction) {
  test::TestServer s(served);
  auto c = s.client();
  const auto a = ok(post(c, "/api/skull/sessions", quick_session()), 201);
  ASSERT_TRUE(a.is_object());
  const std::vector<float> before = floats(a["face"]["positions_f32"]);
  const nlohmann::json direct = direct_violations();
  const auto counted = ok(c.Get(session_path(a, "/violations").c_str()));
  expect_counts(counted, direct);
  EXPECT_TRUE(counted["recounted"].get<bool>());
  EXPECT_FALSE(ok(c.Get(session_path(a, "/violations").c_str()))["recounted"].get<bool>());  // kept
  // All counts, as the direct reconstruction's.
  const auto all = ok(c.Get(session_path(a, "/violations?all=1").c_str()));
  expect_counts(all, direct);
  ASSERT_TRUE(all.contains("counts"));
  EXPECT_TRUE(all["counts"]["current"].get<bool>());
  for (const char* key : {"given_pairs_only", "with_interpolated_landmarks"}) {
    EXPECT_EQ(all["counts"][key]["skull_outside_skin"], direct[key]["skull_outside_skin"]) << key;
    EXPECT_EQ(all["counts"][key]["skin_inside_skull"], direct[key]["skin_inside_skull"]) << key;
  }

  const auto removed = ok(c.Delete(session_path(a, "/landmarks/pg").c_str()));
  ASSERT_TRUE(removed.is_object());
  EXPECT_EQ(removed["removed"], "pg");
  EXPECT_EQ(removed["landmarks"].size(), a["landmarks"].size() - 1);
  EXPECT_TRUE(landmark(removed["landmarks"], "pg").is_null());
  EXPECT_TRUE(landmark(removed["addable"], "pg").is_object());
  EXPECT_GT(largest_difference(before, floats(removed["face"]["positions_f32"])), 0.1);  // mm
  const auto recounted = ok(c.Get(session_path(a, "/violations").c_str()));
  EXPECT_TRUE(recounted["recounted"].get<bool>());
  expect_counts(recounted, direct_violations("pg"));

  // Gone already, never a landmark, or an unknown session: 404.
  EXPECT_EQ(error_of(c.Delete(session_path(a, "/landmarks/pg").c_str()), 404)["field"], "name");
  EXPECT_EQ(error_of(c.Delete(session_path(a, "/landmarks/nolandmark").c_str()), 404)["field"], "name");
  error_of(c.Delete("/api/skull/sessions/nosuch/landmarks/g"), 404);
  error_of(c.Get("/api/skull/sessions/nosuch/violations"), 404);
}

TEST_F(SkullApi, RemovalIsRefusedWhenTooFewWarpPairsWouldRemain) {
  const auto head = test::shared_skull_templates()->get("coarse");
  const LandmarkSet all = template_skull_landmarks(*head);
  LandmarkSet five("five");
  for (const std::string name : {"g", "pg", "zy_L", "zy_R", "v"}) five.add(all.at(name));
  std::ofstream(served / "five.mrk.json") << markups_json_text(five);
  test::TestServer s(served);
  auto c = s.client();
  const auto a = ok(post(c, "/api/skull/sessions", quick_session("five.mrk.json")), 201);
  ASSERT_TRUE(a.is_object());
  const auto four = ok(c.Delete(session_path(a, "/landmarks/v").c_str()));
  ASSERT_TRUE(four.is_object());
  EXPECT_EQ(four["landmarks"].size(), 4u);
  const nlohmann::json e = error_of(c.Delete(session_path(a, "/landmarks/glabella").c_str()), 400);
  ASSERT_TRUE(e.is_object());
  EXPECT_EQ(e["field"], "name");
  EXPECT_NE(e["message"].get<std::string>().find("at least 4"), std::string::npos) << e.dump();
  // The refused removal left the session as it was.
  const auto now = ok(c.Get(session_path(a, "?geometry=0").c_str()));
  EXPECT_EQ(now["landmarks"].size(), 4u);
  EXPECT_EQ(largest_difference(floats(now["face"]["positions_f32"]), floats(four["face"]["positions_f32"])), 0.0);
}
