#include "craniofacial/template_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <set>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "craniofacial/landmark_vocabulary.hpp"

namespace forensim {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "forensim-template";

// Binary arrays: little-endian float64 or int32, as the machines forensim runs on store them.
static_assert(sizeof(double) == 8 && sizeof(std::int32_t) == 4);

template <typename T>
json binary_of(const T* data, std::size_t count) {
  std::vector<std::uint8_t> bytes(count * sizeof(T));
  if (count > 0) std::memcpy(bytes.data(), data, bytes.size());
  return json::binary(std::move(bytes));
}

json doubles(const std::vector<Vec3>& v) {
  std::vector<double> flat;
  flat.reserve(v.size() * 3);
  for (const Vec3& p : v) flat.insert(flat.end(), {p.x(), p.y(), p.z()});
  return binary_of(flat.data(), flat.size());
}

json doubles(const std::vector<Vec2>& v) {
  std::vector<double> flat;
  flat.reserve(v.size() * 2);
  for (const Vec2& p : v) flat.insert(flat.end(), {p.x(), p.y()});
  return binary_of(flat.data(), flat.size());
}

json ints(const std::vector<Tri>& v) {
  std::vector<std::int32_t> flat;
  flat.reserve(v.size() * 3);
  for (const Tri& t : v) flat.insert(flat.end(), {t[0], t[1], t[2]});
  return binary_of(flat.data(), flat.size());
}

json vec(const Vec3& v) {
  return json::array({v.x(), v.y(), v.z()});
}

json mesh_json(const TriMesh& m) {
  return {{"positions", doubles(m.positions)},
          {"triangles", ints(m.triangles)},
          {"normals", doubles(m.normals)},
          {"uvs", doubles(m.uvs)},
          {"triangle_uvs", ints(m.triangle_uvs)}};
}

/// Reading: every access checked, errors naming the file and the field.
class Reader {
 public:
  explicit Reader(std::string source) : m_source(std::move(source)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(m_source, field, problem);
  }

  const json& member(const json& object, const std::string& key, const std::string& where) const {
    if (!object.is_object()) fail(where, "is not a map");
    const auto it = object.find(key);
    if (it == object.end()) fail(where.empty() ? key : where + "/" + key, "is missing");
    return *it;
  }

  void only_keys(const json& object, std::initializer_list<const char*> keys, const std::string& where) const {
    const std::set<std::string> known(keys.begin(), keys.end());
    for (const auto& [key, value] : object.items()) {
      if (!known.count(key)) fail(where.empty() ? key : where + "/" + key, "is not a key of a forensim template");
    }
  }

  double number(const json& j, const std::string& where) const {
    if (!j.is_number()) fail(where, "is not a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) fail(where, "is not finite");
    return v;
  }

  std::string text(const json& j, const std::string& where) const {
    if (!j.is_string()) fail(where, "is not a string");
    return j.get<std::string>();
  }

  Vec3 point(const json& j, const std::string& where) const {
    if (!j.is_array() || j.size() != 3) fail(where, "is not a list of 3 numbers");
    return Vec3(number(j[0], where), number(j[1], where), number(j[2], where));
  }

  template <typename T>
  std::vector<T> binary(const json& j, std::size_t group, const std::string& where) const {
    if (!j.is_binary()) fail(where, "is not a binary array");
    const auto& bytes = j.get_binary();
    if (bytes.size() % (sizeof(T) * group) != 0) {
      fail(where, fmt::format("holds {} bytes, not a whole number of {}-byte groups", bytes.size(), sizeof(T) * group));
    }
    std::vector<T> out(bytes.size() / sizeof(T));
    if (!out.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
  }

  std::vector<Vec3> points(const json& j, const std::string& where) const {
    const auto flat = binary<double>(j, 3, where);
    std::vector<Vec3> out(flat.size() / 3);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = Vec3(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
    return out;
  }

  std::vector<Tri> tris(const json& j, const std::string& where) const {
    const auto flat = binary<std::int32_t>(j, 3, where);
    std::vector<Tri> out(flat.size() / 3);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
    return out;
  }

  TriMesh mesh(const json& j, const std::string& where) const {
    only_keys(j, {"positions", "triangles", "normals", "uvs", "triangle_uvs"}, where);
    TriMesh m;
    m.positions = points(member(j, "positions", where), where + "/positions");
    m.triangles = tris(member(j, "triangles", where), where + "/triangles");
    m.normals = points(member(j, "normals", where), where + "/normals");
    const auto uv = binary<double>(member(j, "uvs", where), 2, where + "/uvs");
    m.uvs.resize(uv.size() / 2);
    for (std::size_t i = 0; i < m.uvs.size(); ++i) m.uvs[i] = Vec2(uv[2 * i], uv[2 * i + 1]);
    m.triangle_uvs = tris(member(j, "triangle_uvs", where), where + "/triangle_uvs");
    if (m.triangles.empty()) fail(where, "has no triangles");
    if (!m.normals.empty() && m.normals.size() != m.positions.size()) fail(where + "/normals", "count differs");
    // TriMesh::validate checks indices, sizes and finiteness; its message names the array.
    try {
      m.validate(where);
    } catch (const InputError& e) {
      fail(where, e.location().empty() ? e.problem() : e.location() + ": " + e.problem());
    }
    return m;
  }

 private:
  std::string m_source;
};

}  // namespace

std::string encode_template_head(const TemplateHead& head) {
  json j;
  j["format"] = kFormat;
  j["version"] = kTemplateFileVersion;
  j["source"] = head.source;
  j["skin"] = mesh_json(head.skin);
  j["skull"] = mesh_json(head.skull);
  j["triangle_chart"] = binary_of(head.triangle_chart.data(), head.triangle_chart.size());
  j["chart_names"] = head.chart_names;
  j["uv_l2_stretch"] = head.uv_l2_stretch;
  j["uv_overlap_free"] = head.uv_overlap_free;
  json pairs = json::array();
  for (const TemplateLandmarkPair& p : head.landmarks) {
    pairs.push_back({{"bone", p.bone_name},
                     {"skin", p.skin_name},
                     {"skull", vec(p.skull)},
                     {"skull_normal", vec(p.skull_normal)},
                     {"skin_point", vec(p.skin)},
                     {"depth_mm", p.depth_mm},
                     {"midline", p.midline}});
  }
  j["landmarks"] = std::move(pairs);
  json skin_only = json::array();
  for (const TemplateSkinLandmark& l : head.skin_landmarks)
    skin_only.push_back({{"name", l.name}, {"position", vec(l.position)}});
  j["skin_landmarks"] = std::move(skin_only);
  json muscles = json::array();
  for (const MuscleLayout& m : head.muscles) {
    muscles.push_back({{"name", m.name},
                       {"kind", m.kind == MuscleKind::sphincter ? "sphincter" : "linear"},
                       {"fibres", m.fibre_count},
                       {"samples", m.samples_per_fibre},
                       {"thickness_mm", m.thickness_mm},
                       {"grid", doubles(m.grid)}});
  }
  j["muscles"] = std::move(muscles);
  if (!head.texture_png.empty()) {
    j["texture_png"] = json::binary(std::vector<std::uint8_t>(head.texture_png.begin(), head.texture_png.end()));
  }
  const std::vector<std::uint8_t> cbor = json::to_cbor(j);
  return std::string(cbor.begin(), cbor.end());
}

TemplateHead decode_template_head(const std::string& bytes, const std::string& source) {
  const Reader r(source);
  json j;
  try {
    j = json::from_cbor(bytes);
  } catch (const json::exception& e) {
    r.fail("", fmt::format("is not a forensim template (not CBOR: {})", e.what()));
  }
  if (!j.is_object() || !j.contains("format") || !j["format"].is_string() || j["format"] != kFormat) {
    r.fail("format", "is not a forensim template (no format \"forensim-template\")");
  }
  r.only_keys(j,
              {"format", "version", "source", "skin", "skull", "triangle_chart", "chart_names", "uv_l2_stretch",
               "uv_overlap_free", "landmarks", "skin_landmarks", "muscles", "texture_png"},
              "");
  const json& version = r.member(j, "version", "");
  if (!version.is_number_integer() || version.get<int>() != kTemplateFileVersion) {
    r.fail("version", fmt::format("is {}; this forensim reads version {}", version.dump(), kTemplateFileVersion));
  }
  TemplateHead head;
  head.source = r.text(r.member(j, "source", ""), "source");
  head.skin = r.mesh(r.member(j, "skin", ""), "skin");
  head.skull = r.mesh(r.member(j, "skull", ""), "skull");
  head.triangle_chart = r.binary<std::int32_t>(r.member(j, "triangle_chart", ""), 1, "triangle_chart");
  const json& names = r.member(j, "chart_names", "");
  if (!names.is_array()) r.fail("chart_names", "is not a list");
  for (std::size_t i = 0; i < names.size(); ++i)
    head.chart_names.push_back(r.text(names[i], fmt::format("chart_names/{}", i)));
  if (!head.triangle_chart.empty()) {
    if (head.triangle_chart.size() != head.skin.triangles.size()) {
      r.fail("triangle_chart", fmt::format("has {} entries for {} skin triangles", head.triangle_chart.size(),
                                           head.skin.triangles.size()));
    }
    for (int c : head.triangle_chart) {
      if (c < 0 || static_cast<std::size_t>(c) >= head.chart_names.size()) {
        r.fail("triangle_chart", fmt::format("chart {} is not one of the {} chart names", c, head.chart_names.size()));
      }
    }
  }
  head.uv_l2_stretch = r.number(r.member(j, "uv_l2_stretch", ""), "uv_l2_stretch");
  const json& overlap = r.member(j, "uv_overlap_free", "");
  if (!overlap.is_boolean()) r.fail("uv_overlap_free", "is not true or false");
  head.uv_overlap_free = overlap.get<bool>();

  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const json& pairs = r.member(j, "landmarks", "");
  if (!pairs.is_array() || pairs.empty()) r.fail("landmarks", "is not a list of landmark pairs");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string where = fmt::format("landmarks/{}", i);
    const json& p = pairs[i];
    r.only_keys(p, {"bone", "skin", "skull", "skull_normal", "skin_point", "depth_mm", "midline"}, where);
    TemplateLandmarkPair pair;
    pair.bone_name = vocabulary.canonical_name(r.text(r.member(p, "bone", where), where + "/bone"), source, where);
    pair.skin_name = vocabulary.canonical_name(r.text(r.member(p, "skin", where), where + "/skin"), source, where);
    if (!seen.insert(pair.skin_name).second) r.fail(where + "/skin", "'" + pair.skin_name + "' is given twice");
    pair.skull = r.point(r.member(p, "skull", where), where + "/skull");
    pair.skull_normal = r.point(r.member(p, "skull_normal", where), where + "/skull_normal");
    if (std::abs(pair.skull_normal.norm() - 1.0) > 1e-6) r.fail(where + "/skull_normal", "is not a unit vector");
    pair.skin = r.point(r.member(p, "skin_point", where), where + "/skin_point");
    pair.depth_mm = r.number(r.member(p, "depth_mm", where), where + "/depth_mm");
    if (pair.depth_mm < 0.0) r.fail(where + "/depth_mm", "is negative");
    const json& midline = r.member(p, "midline", where);
    if (!midline.is_boolean()) r.fail(where + "/midline", "is not true or false");
    pair.midline = midline.get<bool>();
    head.landmarks.push_back(std::move(pair));
  }
  const json& skin_only = r.member(j, "skin_landmarks", "");
  if (!skin_only.is_array()) r.fail("skin_landmarks", "is not a list");
  for (std::size_t i = 0; i < skin_only.size(); ++i) {
    const std::string where = fmt::format("skin_landmarks/{}", i);
    r.only_keys(skin_only[i], {"name", "position"}, where);
    TemplateSkinLandmark l;
    l.name = vocabulary.canonical_name(r.text(r.member(skin_only[i], "name", where), where + "/name"), source, where);
    l.position = r.point(r.member(skin_only[i], "position", where), where + "/position");
    head.skin_landmarks.push_back(std::move(l));
  }
  const json& muscles = r.member(j, "muscles", "");
  if (!muscles.is_array()) r.fail("muscles", "is not a list");
  for (std::size_t i = 0; i < muscles.size(); ++i) {
    const std::string where = fmt::format("muscles/{}", i);
    const json& m = muscles[i];
    r.only_keys(m, {"name", "kind", "fibres", "samples", "thickness_mm", "grid"}, where);
    MuscleLayout layout;
    layout.name = r.text(r.member(m, "name", where), where + "/name");
    const std::string kind = r.text(r.member(m, "kind", where), where + "/kind");
    if (kind != "linear" && kind != "sphincter") r.fail(where + "/kind", "is '" + kind + "', not linear or sphincter");
    layout.kind = kind == "sphincter" ? MuscleKind::sphincter : MuscleKind::linear;
    const json& fibres = r.member(m, "fibres", where);
    const json& samples = r.member(m, "samples", where);
    if (!fibres.is_number_integer() || !samples.is_number_integer() || fibres.get<long long>() < 1 ||
        samples.get<long long>() < 2 || fibres.get<long long>() > 1000 || samples.get<long long>() > 1000) {
      r.fail(where, "fibres must be a whole number in [1, 1000] and samples in [2, 1000]");
    }
    layout.fibre_count = fibres.get<int>();
    layout.samples_per_fibre = samples.get<int>();
    layout.thickness_mm = r.number(r.member(m, "thickness_mm", where), where + "/thickness_mm");
    if (layout.thickness_mm < 0.0) r.fail(where + "/thickness_mm", "is negative");
    layout.grid = r.points(r.member(m, "grid", where), where + "/grid");
    if (layout.grid.size() != static_cast<std::size_t>(layout.fibre_count * layout.samples_per_fibre)) {
      r.fail(where + "/grid", fmt::format("holds {} points, not fibres x samples = {}", layout.grid.size(),
                                          layout.fibre_count * layout.samples_per_fibre));
    }
    for (const Vec3& p : layout.grid) {
      if (!p.allFinite()) r.fail(where + "/grid", "holds a point that is not finite");
    }
    head.muscles.push_back(std::move(layout));
  }
  if (j.contains("texture_png")) {
    const json& t = j["texture_png"];
    if (!t.is_binary()) r.fail("texture_png", "is not binary PNG data");
    const auto& b = t.get_binary();
    static const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (b.size() < 8 || std::memcmp(b.data(), magic, 8) != 0) r.fail("texture_png", "is not a PNG image");
    if (!head.skin.has_uvs()) r.fail("texture_png", "is given but the skin has no UVs");
    head.texture_png.assign(b.begin(), b.end());
  }
  return head;
}

void write_template_head(const std::filesystem::path& path, const TemplateHead& head) {
  write_file_atomic(path, encode_template_head(head));
}

TemplateHead read_template_head(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw IoError(path.string(), "does not exist");
  return decode_template_head(read_file(path, std::size_t{2} << 30), path.string());
}

}  // namespace forensim
