#include "server/skull_session.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/run_folder.hpp"
#include "core/timer.hpp"
#include "craniofacial/face_guides_job.hpp"
#include "craniofacial/landmark_io.hpp"
#include "craniofacial/landmark_vocabulary.hpp"
#include "craniofacial/skull_skin_violations.hpp"
#include "craniofacial/tissue_depth_table.hpp"
#include "mesh_io/gltf_writer.hpp"
#include "reconstruct/reconstruct_inputs.hpp"
#include "server/api_error.hpp"
#include "server/mesh_arrays.hpp"

namespace forensim {
namespace {

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

nlohmann::json vec_json(const Vec3& v) {
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

double ms(double seconds) {
  return std::round(seconds * 1e6) / 1e3;
}

// Runs `body`, answering the library's input and file errors as 400 on `field`.
template <typename F>
auto as_bad_request(const std::string& field, F&& body) {
  try {
    return body();
  } catch (const ApiError&) {
    throw;
  } catch (const Error& e) {
    throw ApiError(400, e.what(), field);
  }
}

}  // namespace

TissueDepths select_session_depths(const SkullDepthChoice& choice) {
  const TissueDepthTable table = tissue_depth_table(reconstruct_table_name(choice.table));
  const TissueDepthQuery query{choice.sex, "", ""};
  if (choice.build.empty()) return select_tissue_depths(table, query);
  return build_variants(table, query, 1.0).of(choice.build);
}

namespace {

/// The reconstruction job of a session request: what forensim reconstruct runs for the same skull.
ReconstructJob session_job(const SkullSessionRequest& request) {
  ReconstructJob job;
  job.skull = request.skull;
  job.unit = request.unit;
  job.landmarks = request.landmarks;
  job.table = request.depths.table;
  job.sex = request.depths.sex;
  job.build = request.depths.build;
  job.template_detail = request.template_detail;
  job.interpolated_landmarks = request.interpolated_landmarks;
  if (request.guides) {
    job.guides = *request.guides;
    job.has_guides = true;
  }
  job.expressions.clear();  // asked for per request (glb, save)
  return job;
}

}  // namespace

SkullSession::SkullSession(std::string id, std::shared_ptr<const TemplateHead> head, const SkullSessionRequest& request)
    : m_id(std::move(id)), m_head(std::move(head)), m_request(request), m_depth_choice(request.depths) {
  touch();
  Stopwatch watch;
  // The inputs the reconstruction reads, each answering on its own field: the table and a landmark file (quick),
  // then the skull with everything after it.
  as_bad_request("/table", [&] { return select_session_depths(m_depth_choice); });
  const bool file_landmarks = request.landmarks != "auto" && request.landmarks != "template";
  if (file_landmarks) as_bad_request("/landmarks", [&] { return read_landmarks(request.landmarks); });
  ReconstructInputs in = as_bad_request("/skull", [&] { return prepare_reconstruction(session_job(request), m_head); });
  m_skull = std::move(in.skull);
  m_landmark_origin = file_landmarks ? "file " + request.landmarks_label : in.landmark_origin;
  if (in.detection) {
    const LandmarkDetection& detection = *in.detection;
    m_detection = {{"similarity_scale", detection.registration.similarity.scale},
                   {"similarity_rms_mm", detection.registration.similarity_rms_mm},
                   {"non_rigid_rms_mm", detection.registration.rms_mm},
                   {"template_carried", in.carried},
                   {"skull_completed", in.completion.has_value()}};
    nlohmann::json left_out = nlohmann::json::array();
    for (const auto& [name, reason] : detection.left_out) left_out.push_back({{"name", name}, {"reason", reason}});
    m_detection["left_out"] = left_out;
  }
  if (in.carried) m_fitted_head = in.fitted;
  for (const auto& [stage, seconds] : in.timings.stages()) m_timings_ms[stage] = ms(seconds);
  watch.lap();
  // The violations are counted on request (violations()), not with the face.
  ReconstructionOptions options = in.options;
  options.fit.count_violations = false;
  m_reconstruction = as_bad_request("/landmarks", [&] {
    return std::make_unique<Reconstruction>(*in.fitted, m_skull.mesh, in.landmarks, in.depths, options);
  });
  m_timings_ms["reconstruction"] = ms(watch.lap());
  touch();  // idle from when the session is ready, not from when its building began
}

SkullSession::~SkullSession() = default;

void SkullSession::touch() {
  m_last_used_ns = now_ns();
}

double SkullSession::idle_seconds() const {
  return 1e-9 * static_cast<double>(now_ns() - m_last_used_ns.load());
}

nlohmann::json SkullSession::summary() const {
  std::lock_guard lock(m_mutex);
  return {{"id", m_id},
          {"skull", m_request.skull_label},
          {"landmarks", m_reconstruction->result().skull_landmarks.size()},
          {"idle_s", idle_seconds()}};
}

nlohmann::json SkullSession::landmarks_json() const {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const ReconstructionResult& result = m_reconstruction->result();
  nlohmann::json list = nlohmann::json::array();
  for (const Landmark& l : result.skull_landmarks.landmarks()) {
    nlohmann::json j = {{"name", l.name},
                        {"position_mm", vec_json(l.position_mm)},
                        {"source", to_string(l.source)},
                        {"confidence", l.confidence}};
    if (const auto ref = vocabulary.find(l.name)) {
      const std::string side = side_word(ref->side);
      j["full_name"] = vocabulary.site(*ref).full_name + (side.empty() ? "" : ", " + side);
    }
    const auto& vectors = result.depth_vectors.vectors;
    for (std::size_t i = 0; i < vectors.size(); ++i) {
      if (vectors[i].bone_landmark != l.name) continue;
      j["skull_mm"] = vec_json(vectors[i].bone_mm);
      j["skin_landmark"] = vectors[i].skin_landmark;
      j["skin_mm"] = vec_json(vectors[i].skin_mm);
      j["depth_mm"] = vectors[i].depth_mm;
      j["used_in_warp"] = static_cast<bool>(result.used_in_warp[i]);
    }
    list.push_back(std::move(j));
  }
  return list;
}

nlohmann::json SkullSession::addable_json() const {
  // Bone landmarks of the vocabulary the set lacks. Those with a skin pair on the template and a depth in the
  // table move the face; the others (porion, orbitale, ...) are kept with the landmarks for the export.
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const ReconstructionResult& result = m_reconstruction->result();
  nlohmann::json list = nlohmann::json::array();
  for (const std::string& name : vocabulary.landmark_names(LandmarkSurface::bone)) {
    if (result.skull_landmarks.contains(name)) continue;
    const auto ref = vocabulary.find(name);
    if (!ref) continue;
    const auto pair = vocabulary.paired(*ref);
    const std::string skin = pair ? vocabulary.name(*pair) : "";
    bool on_template = false;
    for (const TemplateLandmarkPair& p : m_head->landmarks) on_template = on_template || (pair && p.skin_name == skin);
    const std::string side = side_word(ref->side);
    list.push_back({{"name", name},
                    {"full_name", vocabulary.site(*ref).full_name + (side.empty() ? "" : ", " + side)},
                    {"skin_landmark", skin},
                    {"moves_face", on_template && m_reconstruction->depths().depth_mm(name).has_value()}});
  }
  return list;
}

nlohmann::json SkullSession::depths_json() const {
  const TissueDepths& d = m_reconstruction->depths();
  return {{"table", m_depth_choice.table_label},
          {"sex", m_depth_choice.sex},
          {"build", m_depth_choice.build},
          {"table_name", d.table},
          {"group", d.group.describe()},
          {"variant", d.variant},
          {"notes", d.notes}};
}

nlohmann::json SkullSession::guide_values_json() const {
  // The values the guides would take to leave the face as it is: from the warped skin landmarks, in the
  // guides' default frame (lateral = +x, up = +z).
  const ReconstructionResult& result = m_reconstruction->result();
  const FaceGuides defaults;
  auto skin = [&](const std::string& name) -> std::optional<Vec3> {
    for (const TemplateSkinLandmark& s : result.skin_only_landmarks)
      if (s.name == name) return s.position;
    if (const Landmark* l = result.skin_landmarks.find(name)) return l->position_mm;
    return std::nullopt;
  };
  nlohmann::json j = nlohmann::json::object();
  if (auto p = skin("al'_L")) j["nasal_aperture_left_mm"] = p->x() - defaults.alar_offset_mm;
  if (auto p = skin("al'_R")) j["nasal_aperture_right_mm"] = p->x() + defaults.alar_offset_mm;
  if (auto p = skin("ch'_L")) j["mouth_corner_left_mm"] = p->x();
  if (auto p = skin("ch'_R")) j["mouth_corner_right_mm"] = p->x();
  if (auto p = skin("ls'")) j["upper_lip_border_mm"] = p->z();
  if (auto p = skin("li'")) j["lower_lip_border_mm"] = p->z();
  if (auto p = skin("sto'")) j["lip_parting_mm"] = p->z();
  if (const auto& g = m_reconstruction->options().guides) {
    const nlohmann::json given = face_guides_json(*g);
    for (auto it = j.begin(); it != j.end(); ++it)
      if (given.contains(it.key())) it.value() = given[it.key()];
  }
  return j;
}

nlohmann::json SkullSession::face_positions_json() const {
  return {{"positions_f32", positions_float32_base64(m_reconstruction->result().skin.positions)}};
}

void SkullSession::changed() {
  m_expressions.reset();
  m_poses.clear();
  ++m_face_version;
}

nlohmann::json SkullSession::record() const {
  nlohmann::json j = {{"skull", m_request.skull_label},
                      {"unit", m_request.unit},
                      {"landmarks", m_request.landmarks_label},
                      {"table", m_depth_choice.table_label},
                      {"sex", m_depth_choice.sex},
                      {"build", m_depth_choice.build},
                      {"template_detail", m_request.template_detail},
                      {"interpolated_landmarks", m_request.interpolated_landmarks}};
  const auto& g = m_reconstruction->options().guides;
  j["guides"] = g ? face_guides_json(*g) : nlohmann::json(nullptr);
  return j;
}

nlohmann::json SkullSession::describe(bool geometry) {
  std::lock_guard lock(m_mutex);
  touch();
  const auto& g = m_reconstruction->options().guides;
  nlohmann::json j = {{"id", m_id},
                      {"request", record()},
                      {"skull",
                       {{"source", m_skull.source},
                        {"kind", m_skull.kind.empty() ? "mesh" : m_skull.kind},
                        {"triangles", m_skull.mesh.triangle_count()},
                        {"notes", m_skull.notes}}},
                      {"template_detail", m_request.template_detail},
                      {"landmark_origin", m_landmark_origin},
                      {"detection", m_detection},
                      {"landmarks", landmarks_json()},
                      {"addable", addable_json()},
                      {"depths", depths_json()},
                      {"guides", g ? face_guides_json(*g) : nlohmann::json(nullptr)},
                      {"guide_values", guide_values_json()},
                      {"expressions", expression_preset_names()},
                      {"timings_ms", m_timings_ms}};
  if (geometry) {
    j["face"] = mesh_arrays_json(m_reconstruction->result().skin);
    j["skull_mesh"] = mesh_arrays_json(m_skull.mesh);
  } else {
    j["face"] = face_positions_json();
  }
  return j;
}

nlohmann::json SkullSession::move_landmark(const LandmarkEdit& edit) {
  std::lock_guard lock(m_mutex);
  touch();
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const std::string canonical =
      as_bad_request("/name", [&] { return vocabulary.canonical_name(edit.name, "landmark", edit.name); });
  const LandmarkRef ref = vocabulary.resolve(canonical, "landmark", canonical);
  if (vocabulary.site(ref).surface != LandmarkSurface::bone) {
    throw ApiError(400, "landmark '" + edit.name + "' lies on the skin; the editor places bone landmarks on the skull",
                   "/name");
  }
  const bool added = !m_reconstruction->result().skull_landmarks.contains(canonical);
  Stopwatch watch;
  const std::size_t changed_targets =
      as_bad_request("/position", [&] { return m_reconstruction->move_landmark(canonical, edit.position_mm); });
  const double update_s = watch.lap();
  changed();
  nlohmann::json j = {{"added", added}, {"changed_targets", changed_targets}, {"update_ms", ms(update_s)}};
  j["landmarks"] = landmarks_json();
  for (const auto& l : j["landmarks"])
    if (l["name"] == canonical) j["landmark"] = l;
  j["addable"] = addable_json();
  j["face"] = face_positions_json();
  j["encode_ms"] = ms(watch.lap());
  return j;
}

nlohmann::json SkullSession::remove_landmark(const std::string& name) {
  std::lock_guard lock(m_mutex);
  touch();
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const auto ref = vocabulary.find(name);
  const std::string canonical = ref ? vocabulary.name(*ref) : name;
  if (!ref || !m_reconstruction->result().skull_landmarks.contains(canonical)) {
    throw ApiError(404, "the session has no landmark '" + name + "'", "name");
  }
  Stopwatch watch;
  const std::size_t pairs = as_bad_request("name", [&] { return m_reconstruction->remove_landmark(canonical); });
  const double update_s = watch.lap();
  changed();
  nlohmann::json j = {{"removed", canonical}, {"warp_pairs", pairs}, {"update_ms", ms(update_s)}};
  j["landmarks"] = landmarks_json();
  j["addable"] = addable_json();
  j["face"] = face_positions_json();
  j["encode_ms"] = ms(watch.lap());
  return j;
}

namespace {

nlohmann::json violations_answer(const SkullSkinViolations& v, std::uint64_t version, bool recounted, double seconds) {
  return {{"skull_through_skin", v.skull_outside_skin},
          {"skin_inside_skull", v.skin_inside_skull},
          {"max_skull_protrusion_mm", v.max_skull_protrusion_mm},
          {"max_skin_intrusion_mm", v.max_skin_intrusion_mm},
          {"face_version", version},
          {"recounted", recounted},
          {"count_ms", ms(seconds)}};
}

}  // namespace

nlohmann::json SkullSession::violations(bool all) {
  Stopwatch watch;
  if (all) {
    std::lock_guard lock(m_mutex);
    touch();
    const bool recount = !m_reconstruction->result().violations_current;
    if (recount) m_reconstruction->recount_violations();
    m_violations = m_reconstruction->result().violations_final;
    m_violations_version = m_face_version;
    nlohmann::json j = violations_answer(*m_violations, m_face_version, recount, watch.seconds());
    j["counts"] = m_reconstruction->violations_json();
    return j;
  }
  TriMesh skin;
  std::uint64_t version = 0;
  {
    std::lock_guard lock(m_mutex);
    touch();
    if (m_violations && m_violations_version == m_face_version) {
      return violations_answer(*m_violations, m_face_version, false, watch.seconds());
    }
    skin = m_reconstruction->result().skin;
    version = m_face_version;
  }
  // The skull mesh does not change after the session's construction.
  SkullSkinViolations v;
  {
    std::lock_guard lock(m_counter_mutex);
    if (!m_counter) m_counter = std::make_unique<SkullSkinViolationCounter>(m_skull.mesh);
    v = m_counter->count(skin);
  }
  {
    std::lock_guard lock(m_mutex);
    if (version == m_face_version) {
      m_violations = v;
      m_violations_version = version;
    }
  }
  return violations_answer(v, version, true, watch.seconds());
}

nlohmann::json SkullSession::set_depths(const SkullDepthChoice& choice) {
  std::lock_guard lock(m_mutex);
  touch();
  Stopwatch watch;
  const TissueDepths depths = as_bad_request("/table", [&] { return select_session_depths(choice); });
  const std::size_t changed_targets = as_bad_request("/table", [&] { return m_reconstruction->set_depths(depths); });
  const double update_s = watch.lap();
  m_depth_choice = choice;
  changed();
  return {{"depths", depths_json()},       {"changed_targets", changed_targets}, {"update_ms", ms(update_s)},
          {"landmarks", landmarks_json()}, {"addable", addable_json()},          {"face", face_positions_json()}};
}

nlohmann::json SkullSession::set_guides(const std::optional<FaceGuides>& guides) {
  std::lock_guard lock(m_mutex);
  touch();
  const std::optional<FaceGuides> before = m_reconstruction->options().guides;
  Stopwatch watch;
  try {
    m_reconstruction->set_guides(guides);
  } catch (const Error& e) {
    m_reconstruction->set_guides(before);  // the guides that worked
    throw ApiError(400, e.what(), "/guides");
  }
  const double update_s = watch.lap();
  changed();
  const ReconstructionResult& result = m_reconstruction->result();
  nlohmann::json adjusted = nlohmann::json::array();
  for (std::size_t i = 0; i < result.guides_adjusted.size(); ++i) {
    adjusted.push_back({{"name", result.guides_adjusted[i]},
                        {"from_mm", vec_json(result.guides_adjusted_from[i])},
                        {"to_mm", vec_json(result.guides_adjusted_to[i])}});
  }
  return {{"guides", guides ? face_guides_json(*guides) : nlohmann::json(nullptr)},
          {"guide_values", guide_values_json()},
          {"guides_adjusted", adjusted},
          {"update_ms", ms(update_s)},
          {"face", face_positions_json()}};
}

const FaceExpressions& SkullSession::expressions_model() {
  if (!m_expressions) {
    const ReconstructionResult& result = m_reconstruction->result();
    m_expressions = std::make_unique<FaceExpressions>(result.skin, m_skull.mesh, result.muscles);
  }
  return *m_expressions;
}

nlohmann::json SkullSession::expression(const std::string& name) {
  std::lock_guard lock(m_mutex);
  touch();
  as_bad_request("/name", [&] { return expression_preset(name); });
  Stopwatch watch;
  const bool cached = m_poses.count(name) > 0;
  if (!cached) m_poses[name] = expressions_model().preset(name).skin_positions;
  const std::vector<Vec3>& pose = m_poses[name];
  const std::vector<Vec3>& neutral = m_reconstruction->result().skin.positions;
  double largest = 0.0;
  for (std::size_t v = 0; v < pose.size(); ++v) largest = std::max(largest, (pose[v] - neutral[v]).norm());
  return {{"name", name},
          {"cached", cached},
          {"seconds", watch.seconds()},
          {"max_displacement_mm", largest},
          {"positions_f32", positions_float32_base64(pose)}};
}

std::string SkullSession::markups(const std::string& which) {
  std::lock_guard lock(m_mutex);
  touch();
  const ReconstructionResult& result = m_reconstruction->result();
  LandmarkSet set = which == "skin" ? result.skin_landmarks : result.skull_landmarks;
  set.set_name(which);
  return markups_json_text(set);
}

std::vector<MorphTarget> SkullSession::morph_targets(const std::vector<std::string>& expressions) {
  std::vector<FaceExpression> poses;
  for (const std::string& name : expressions) {
    as_bad_request("/expressions", [&] { return expression_preset(name); });
    if (!m_poses.count(name)) m_poses[name] = expressions_model().preset(name).skin_positions;
    FaceExpression e;
    e.name = name;
    e.skin_positions = m_poses[name];
    poses.push_back(std::move(e));
  }
  return expression_morph_targets(m_reconstruction->result().skin, poses);
}

namespace {

GltfScene head_scene(const TriMesh& skin, std::vector<MorphTarget> targets, const TriMesh& skull) {
  GltfScene scene;
  GltfMeshNode head_node;
  head_node.name = "head";
  head_node.mesh = skin;
  head_node.mesh.material.name = "skin";
  head_node.morph_targets = std::move(targets);
  scene.nodes.push_back(std::move(head_node));
  GltfMeshNode skull_node;
  skull_node.name = "skull";
  skull_node.mesh = skull;
  skull_node.mesh.material.name = "bone";
  skull_node.mesh.material.base_color = Vec4f(0.85f, 0.8f, 0.7f, 1.0f);
  scene.nodes.push_back(std::move(skull_node));
  return scene;
}

}  // namespace

std::string SkullSession::glb(const std::vector<std::string>& expressions) {
  std::lock_guard lock(m_mutex);
  touch();
  const GltfScene scene = head_scene(m_reconstruction->result().skin, morph_targets(expressions), m_skull.mesh);
  // The glTF writer writes files; encode through a private temporary file.
  static std::atomic<int> counter{0};
  const std::filesystem::path tmp =
      std::filesystem::temp_directory_path() /
      ("forensim-serve-" + std::to_string(::getpid()) + "-skull-" + m_id + "-" + std::to_string(counter++) + ".glb");
  write_gltf(tmp, scene);
  std::string bytes = read_file(tmp);
  std::error_code ec;
  std::filesystem::remove(tmp, ec);
  return bytes;
}

nlohmann::json SkullSession::save(const std::filesystem::path& folder, const std::vector<std::string>& expressions) {
  std::lock_guard lock(m_mutex);
  touch();
  const ReconstructionResult& result = m_reconstruction->result();
  const GltfScene scene = head_scene(result.skin, morph_targets(expressions), m_skull.mesh);
  RunFolder run(folder, "reconstruct");
  run.set_job(record());
  write_gltf(run.file("head.glb"), scene);
  run.add_output("head.glb");
  LandmarkSet skull_set = result.skull_landmarks, skin_set = result.skin_landmarks;
  skull_set.set_name("skull");
  skin_set.set_name("skin");
  write_landmarks(run.file("skull_landmarks.mrk.json"), skull_set);
  run.add_output("skull_landmarks.mrk.json");
  write_landmarks(run.file("skin_landmarks.mrk.json"), skin_set);
  run.add_output("skin_landmarks.mrk.json");
  nlohmann::json provenance = m_reconstruction->provenance();
  provenance["landmarks"]["origin"] = m_landmark_origin;
  provenance["skull"] = {{"source", m_skull.source}, {"kind", m_skull.kind}, {"notes", m_skull.notes}};
  provenance["editor"] = "forensim serve skull editor, session " + m_id;
  run.write("provenance.json", provenance.dump(2));
  run.facts()["landmarks"] = result.skull_landmarks.size();
  run.facts()["expressions"] = expressions.size();
  run.write_record();
  return {
      {"files", {"head.glb", "skull_landmarks.mrk.json", "skin_landmarks.mrk.json", "provenance.json", "run.json"}}};
}

}  // namespace forensim
