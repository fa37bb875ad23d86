#include "craniofacial/landmark_io.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "craniofacial/csv_table.hpp"
#include "craniofacial/landmark_vocabulary.hpp"

namespace forensim {
namespace {

constexpr std::size_t k_max_landmark_file_bytes = std::size_t{64} << 20;
constexpr const char* k_markups_schema =
    "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/"
    "markups-schema-v1.0.3.json#";

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  std::size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

CoordinateSystem parse_system(const std::string& text, const std::string& source, const std::string& location) {
  const std::string t = lower(trim(text));
  if (t == "lps") return CoordinateSystem::lps;
  if (t == "ras") return CoordinateSystem::ras;
  throw InputError(source, location, "coordinate system '" + text + "' is not LPS or RAS");
}

/// The landmark name to store for a label read from a file.
std::string landmark_name(const std::string& label, const LandmarkReadOptions& options, const std::string& source,
                          const std::string& location) {
  const std::string t = trim(label);
  if (t.empty()) throw InputError(source, location, "landmark with an empty label");
  if (options.naming == LandmarkNaming::keep) return t;
  return LandmarkVocabulary::built_in().canonical_name(t, source, location);
}

void add_unique(LandmarkSet& set, Landmark landmark, const std::string& source, const std::string& location,
                std::vector<std::string>& where) {
  if (const auto i = set.index_of(landmark.name)) {
    throw InputError(source, location, "landmark '" + landmark.name + "' is given twice (first at " + where[*i] + ")");
  }
  set.add(std::move(landmark));
  where.push_back(location);
}

/// forensim's fields in a Slicer description: "...; source=detected; confidence=0.8".
void read_description(const std::string& description, Landmark& landmark, const std::string& source,
                      const std::string& location) {
  std::size_t start = 0;
  while (start <= description.size()) {
    std::size_t end = description.find(';', start);
    if (end == std::string::npos) end = description.size();
    const std::string item = trim(description.substr(start, end - start));
    const std::size_t eq = item.find('=');
    if (eq != std::string::npos) {
      const std::string key = lower(trim(item.substr(0, eq)));
      const std::string value = trim(item.substr(eq + 1));
      if (key == "source") {
        landmark.source = parse_landmark_source(value, source, location + ".description");
      } else if (key == "confidence") {
        double c = -1.0;
        const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), c);
        if (ec != std::errc() || ptr != value.data() + value.size() || !(c >= 0.0 && c <= 1.0)) {
          throw InputError(source, location + ".description", "confidence " + value + " is not a number in [0, 1]");
        }
        landmark.confidence = c;
      }
    }
    start = end + 1;
  }
}

std::string description_of(const Landmark& landmark) {
  std::string text;
  if (const auto ref = LandmarkVocabulary::built_in().find(landmark.name)) {
    const LandmarkVocabulary& v = LandmarkVocabulary::built_in();
    text = v.site(*ref).full_name;
    if (ref->side != Side::none) text += ", " + side_word(ref->side);
    text += "; ";
  }
  text += "source=" + to_string(landmark.source) + "; confidence=" + fmt::format("{}", landmark.confidence);
  return text;
}

std::string line_column(const std::string& text, std::size_t byte) {
  int line = 1, column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

/// The value of `key` in a JSON object, or nullptr.
const nlohmann::json* member(const nlohmann::json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

enum class LandmarkFormat { markups, csv };

LandmarkFormat format_of(const std::filesystem::path& path) {
  const std::string name = lower(path.filename().string());
  if (ends_with(name, ".json")) return LandmarkFormat::markups;
  if (ends_with(name, ".csv")) return LandmarkFormat::csv;
  if (ends_with(name, ".fcsv")) {
    throw InputError(path.string(), "",
                     "Slicer's legacy .fcsv is not read; save the markups as .mrk.json in Slicer (or export CSV)");
  }
  throw InputError(path.string(), "", "unknown landmark file type (expected .mrk.json or .csv)");
}

}  // namespace

std::string to_string(CoordinateSystem system) {
  return system == CoordinateSystem::ras ? "RAS" : "LPS";
}

Vec3 to_lps(const Vec3& point, CoordinateSystem system) {
  return system == CoordinateSystem::ras ? Vec3(-point.x(), -point.y(), point.z()) : point;
}

Vec3 from_lps(const Vec3& point_lps, CoordinateSystem system) {
  return to_lps(point_lps, system);
}

LandmarkSet parse_markups_json(const std::string& text, const std::string& source, const LandmarkReadOptions& options) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(source, line_column(text, e.byte > 0 ? e.byte - 1 : 0), std::string("invalid JSON: ") + e.what());
  } catch (const nlohmann::json::exception& e) {  // e.g. a number too large for a double
    throw InputError(source, "", std::string("invalid JSON: ") + e.what());
  }
  if (!doc.is_object()) throw InputError(source, "", "markups file must hold a JSON object");
  const nlohmann::json* markups = member(doc, "markups");
  if (markups == nullptr) throw InputError(source, "", "no \"markups\" array (not a Slicer markups file?)");
  if (!markups->is_array()) throw InputError(source, "markups", "\"markups\" must be an array");

  LandmarkSet set(source);
  std::vector<std::string> where;
  int fiducials = 0;
  std::size_t m = 0;
  for (const nlohmann::json& markup : *markups) {
    const std::string mloc = "markups[" + std::to_string(m++) + "]";
    if (!markup.is_object()) throw InputError(source, mloc, "markup must be an object");
    const nlohmann::json* type = member(markup, "type");
    if (type == nullptr || !type->is_string()) throw InputError(source, mloc + ".type", "missing markup type");
    if (type->get<std::string>() != "Fiducial") continue;
    ++fiducials;
    CoordinateSystem system = CoordinateSystem::lps;
    if (const nlohmann::json* cs = member(markup, "coordinateSystem")) {
      if (!cs->is_string()) throw InputError(source, mloc + ".coordinateSystem", "must be \"LPS\" or \"RAS\"");
      system = parse_system(cs->get<std::string>(), source, mloc + ".coordinateSystem");
    }
    if (const nlohmann::json* units = member(markup, "coordinateUnits")) {
      if (!units->is_string() || units->get<std::string>() != "mm") {
        throw InputError(source, mloc + ".coordinateUnits",
                         "coordinate units " + units->dump() + " are not supported (only \"mm\")");
      }
    }
    const nlohmann::json* points = member(markup, "controlPoints");
    if (points == nullptr) continue;  // an empty list is written without controlPoints
    if (!points->is_array()) throw InputError(source, mloc + ".controlPoints", "must be an array");
    std::size_t p = 0;
    for (const nlohmann::json& point : *points) {
      const std::string ploc = mloc + ".controlPoints[" + std::to_string(p++) + "]";
      if (!point.is_object()) throw InputError(source, ploc, "control point must be an object");
      if (const nlohmann::json* status = member(point, "positionStatus")) {
        if (!status->is_string()) throw InputError(source, ploc + ".positionStatus", "must be a string");
        if (status->get<std::string>() != "defined") continue;  // no position was placed
      }
      const nlohmann::json* label = member(point, "label");
      if (label == nullptr || !label->is_string()) {
        throw InputError(source, ploc + ".label", "missing or not a string");
      }
      Landmark landmark;
      landmark.name = landmark_name(label->get<std::string>(), options, source, ploc + ".label");
      landmark.source = LandmarkSource::imported;
      const nlohmann::json* position = member(point, "position");
      if (position == nullptr || !position->is_array()) {
        throw InputError(source, ploc + ".position", "must be an array of three numbers");
      }
      std::vector<double> xyz;
      for (const nlohmann::json& v : *position) {
        if (!v.is_number()) throw InputError(source, ploc + ".position", "holds a value that is not a number");
        xyz.push_back(v.get<double>());
      }
      if (xyz.size() != 3) throw InputError(source, ploc + ".position", "must be an array of three numbers");
      const Vec3 q(xyz[0], xyz[1], xyz[2]);
      if (!q.allFinite()) throw InputError(source, ploc + ".position", "is not finite");
      landmark.position_mm = to_lps(q, system);
      if (const nlohmann::json* description = member(point, "description")) {
        if (!description->is_string()) throw InputError(source, ploc + ".description", "must be a string");
        read_description(description->get<std::string>(), landmark, source, ploc);
      }
      add_unique(set, std::move(landmark), source, ploc, where);
    }
  }
  if (fiducials == 0) throw InputError(source, "markups", "no markup of type \"Fiducial\" (point list)");
  return set;
}

std::string markups_json_text(const LandmarkSet& set, const LandmarkWriteOptions& options) {
  nlohmann::ordered_json points = nlohmann::ordered_json::array();
  const bool ras = options.coordinate_system == CoordinateSystem::ras;
  for (std::size_t i = 0; i < set.size(); ++i) {
    const Landmark& l = set[i];
    const Vec3 p = from_lps(l.position_mm, options.coordinate_system);
    nlohmann::ordered_json point;
    point["id"] = std::to_string(i + 1);
    point["label"] = l.name;
    point["description"] = description_of(l);
    point["associatedNodeID"] = "";
    point["position"] = {p.x(), p.y(), p.z()};
    // Slicer's default orientation for each system (identity in RAS, x and y flipped in LPS).
    point["orientation"] =
        ras ? std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1} : std::vector<double>{-1, 0, 0, 0, -1, 0, 0, 0, 1};
    point["selected"] = true;
    point["locked"] = false;
    point["visibility"] = true;
    point["positionStatus"] = "defined";
    points.push_back(std::move(point));
  }
  nlohmann::ordered_json markup;
  markup["type"] = "Fiducial";
  markup["coordinateSystem"] = to_string(options.coordinate_system);
  markup["coordinateUnits"] = "mm";
  markup["locked"] = false;
  markup["fixedNumberOfControlPoints"] = false;
  markup["labelFormat"] = "%N-%d";
  markup["lastUsedControlPointNumber"] = set.size();
  markup["controlPoints"] = std::move(points);
  markup["measurements"] = nlohmann::ordered_json::array();
  nlohmann::ordered_json doc;
  doc["@schema"] = k_markups_schema;
  doc["markups"] = nlohmann::ordered_json::array({std::move(markup)});
  return doc.dump(4) + "\n";
}

LandmarkSet parse_landmark_csv(const std::string& text, const std::string& source, const LandmarkReadOptions& options) {
  const CsvTable table = parse_csv(text, source);
  check_csv_columns(table, {"name", "x", "y", "z"}, {"source", "confidence"});
  CoordinateSystem system = CoordinateSystem::lps;
  if (options.csv_coordinate_system) {
    system = *options.csv_coordinate_system;
  } else {
    for (const std::string& comment : table.comments) {
      const std::string c = lower(comment);
      const std::string key = "coordinate system:";
      if (c.rfind(key, 0) == 0) {
        std::string word = trim(c.substr(key.size()));
        word = word.substr(0, word.find_first_of(" ,;"));
        system = parse_system(word, source, "comment");
      }
    }
  }
  const std::size_t name_col = *table.column("name");
  const std::size_t xyz_col[3] = {*table.column("x"), *table.column("y"), *table.column("z")};
  const auto source_col = table.column("source");
  const auto confidence_col = table.column("confidence");
  LandmarkSet set(source);
  std::vector<std::string> where;
  for (const CsvRow& row : table.rows) {
    const std::string location = "line " + std::to_string(row.line);
    Landmark landmark;
    landmark.name = landmark_name(row.fields[name_col], options, source, location + ", field name");
    Vec3 p;
    for (int k = 0; k < 3; ++k) {
      p[k] = parse_csv_number(row.fields[xyz_col[k]], source, row.line, table.columns[xyz_col[k]]);
    }
    landmark.position_mm = to_lps(p, system);
    landmark.source = LandmarkSource::imported;
    if (source_col && !row.fields[*source_col].empty()) {
      landmark.source = parse_landmark_source(row.fields[*source_col], source, location + ", field source");
    }
    if (confidence_col && !row.fields[*confidence_col].empty()) {
      const double c = parse_csv_number(row.fields[*confidence_col], source, row.line, "confidence");
      if (!(c >= 0.0 && c <= 1.0)) {
        throw InputError(source, location + ", field confidence",
                         "confidence " + row.fields[*confidence_col] + " is outside [0, 1]");
      }
      landmark.confidence = c;
    }
    add_unique(set, std::move(landmark), source, location, where);
  }
  return set;
}

std::string landmark_csv_text(const LandmarkSet& set, const LandmarkWriteOptions& options) {
  std::string out = "# coordinate system: " + to_string(options.coordinate_system) + ", millimetres\n";
  out += "name,x,y,z,source,confidence\n";
  for (const Landmark& l : set.landmarks()) {
    const Vec3 p = from_lps(l.position_mm, options.coordinate_system);
    out += csv_field(l.name) + fmt::format(",{},{},{},", p.x(), p.y(), p.z()) + to_string(l.source) +
           fmt::format(",{}\n", l.confidence);
  }
  return out;
}

LandmarkSet read_landmarks(const std::filesystem::path& path, const LandmarkReadOptions& options) {
  const LandmarkFormat format = format_of(path);
  const std::string text = read_file(path, k_max_landmark_file_bytes);
  LandmarkSet set = format == LandmarkFormat::markups ? parse_markups_json(text, path.string(), options)
                                                      : parse_landmark_csv(text, path.string(), options);
  set.set_name(path.filename().string());
  return set;
}

void write_landmarks(const std::filesystem::path& path, const LandmarkSet& set, const LandmarkWriteOptions& options) {
  const LandmarkFormat format = format_of(path);
  write_file_atomic(
      path, format == LandmarkFormat::markups ? markups_json_text(set, options) : landmark_csv_text(set, options));
}

}  // namespace forensim
