#include "core/job.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace forensim {
namespace {

std::string escape_pointer_token(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

// Line and column (1-based) of a byte offset in text.
std::pair<std::size_t, std::size_t> line_column(const std::string& text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < std::min(offset, text.size()); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

void find_unused(const nlohmann::json& node, const std::string& pointer, const std::set<std::string>& used,
                 std::string& first_unused, std::vector<std::string>& siblings) {
  if (!first_unused.empty() || !node.is_object()) return;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string child = pointer + "/" + escape_pointer_token(it.key());
    if (!used.count(child)) {
      first_unused = child;
      siblings.clear();
      for (const auto& key : used) {
        // Known keys at the same level.
        if (key.rfind(pointer + "/", 0) == 0 && key.find('/', pointer.size() + 1) == std::string::npos) {
          siblings.push_back(key.substr(pointer.size() + 1));
        }
      }
      return;
    }
    if (it.value().is_object()) find_unused(it.value(), child, used, first_unused, siblings);
    if (it.value().is_array()) {
      for (std::size_t i = 0; i < it.value().size(); ++i) {
        find_unused(it.value()[i], child + "/" + std::to_string(i), used, first_unused, siblings);
      }
    }
    if (!first_unused.empty()) return;
  }
}

}  // namespace

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

JobDocument JobDocument::parse(const std::string& text, const std::string& source) {
  JobDocument doc;
  doc.m_state = std::make_shared<State>();
  doc.m_state->source = source;
  try {
    doc.m_state->json = nlohmann::json::parse(text, nullptr, true, /*ignore_comments=*/true);
  } catch (const nlohmann::json::parse_error& e) {
    const auto [line, column] = line_column(text, e.byte == 0 ? 0 : e.byte - 1);
    throw JobError(
        source, "",
        "JSON syntax error at line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + e.what());
  } catch (const nlohmann::json::exception& e) {
    // A number beyond a double's range ("1e999") fails as out_of_range, not as a parse_error.
    throw JobError(source, "", std::string("JSON value out of range: ") + e.what());
  }
  if (!doc.m_state->json.is_object()) {
    throw JobError(source, "", std::string("a job must be a JSON object, got ") + doc.m_state->json.type_name());
  }
  return doc;
}

JobDocument JobDocument::load(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), "cannot open job file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  constexpr std::size_t max_job_bytes = 64u << 20;
  if (buffer.str().size() > max_job_bytes) throw JobError(path.string(), "", "job file is larger than 64 MiB");
  return parse(buffer.str(), path.string());
}

JobDocument JobDocument::empty(const std::string& source) {
  return parse("{}", source);
}

JobNode JobDocument::root() {
  return JobNode(m_state, "");
}

void JobDocument::check_all_used() const {
  std::string first;
  std::vector<std::string> siblings;
  find_unused(m_state->json, "", m_state->used, first, siblings);
  if (first.empty()) return;
  const std::string key = first.substr(first.rfind('/') + 1);
  std::string message = "unknown key '" + key + "'";
  std::string best;
  std::size_t best_distance = 3;
  for (const auto& s : siblings) {
    const std::size_t d = edit_distance(key, s);
    if (d < best_distance) {
      best_distance = d;
      best = s;
    }
  }
  if (!best.empty()) message += " (did you mean '" + best + "'?)";
  throw JobError(m_state->source, first, message);
}

std::string JobNode::key_pointer(const std::string& key) const {
  return m_pointer + "/" + escape_pointer_token(key);
}

const nlohmann::json* JobNode::lookup(const std::string& key) const {
  const nlohmann::json::json_pointer ptr(m_pointer);
  if (!m_state->json.contains(ptr)) return nullptr;
  const nlohmann::json& object = m_state->json.at(ptr);
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

bool JobNode::has(const std::string& key) const {
  return lookup(key) != nullptr;
}

void JobNode::record(const std::string& key, const nlohmann::json& value) const {
  const std::string pointer = key_pointer(key);
  m_state->used.insert(pointer);
  // Parents count as used too.
  for (std::string p = m_pointer; !p.empty(); p = p.substr(0, p.rfind('/'))) m_state->used.insert(p);
  if (!value.is_object()) m_state->resolved[nlohmann::json::json_pointer(pointer)] = value;
}

void JobNode::fail(const std::string& key, const std::string& problem) const {
  throw JobError(m_state->source, key.empty() ? m_pointer : key_pointer(key), problem);
}

double JobNode::get_number(const std::string& key, double fallback, double lo, double hi) const {
  const double value = get<double>(key, fallback);
  if (!std::isfinite(value) || value < lo || value > hi) {
    std::ostringstream s;
    s << "value " << value << " is outside [" << lo << ", " << hi << "]";
    fail(key, s.str());
  }
  return value;
}

long long JobNode::get_integer(const std::string& key, long long fallback, long long lo, long long hi) const {
  const long long value = get<long long>(key, fallback);
  if (value < lo || value > hi) {
    fail(key,
         "value " + std::to_string(value) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return value;
}

std::string JobNode::get_choice(const std::string& key, const std::string& fallback,
                                const std::vector<std::string>& choices) const {
  const std::string value = get<std::string>(key, fallback);
  if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    fail(key, "'" + value + "' is not one of: " + list);
  }
  return value;
}

JobNode JobNode::child(const std::string& key) const {
  const nlohmann::json* value = lookup(key);
  const std::string pointer = key_pointer(key);
  if (value != nullptr && !value->is_object()) {
    fail(key, std::string("expected an object, got ") + value->type_name());
  }
  m_state->used.insert(pointer);
  for (std::string p = m_pointer; !p.empty(); p = p.substr(0, p.rfind('/'))) m_state->used.insert(p);
  if (!m_state->resolved.contains(nlohmann::json::json_pointer(pointer))) {
    m_state->resolved[nlohmann::json::json_pointer(pointer)] = nlohmann::json::object();
  }
  if (value == nullptr) {
    // Absent: an empty object so that defaults apply; lookups find nothing.
    return JobNode(m_state, pointer);
  }
  return JobNode(m_state, pointer);
}

std::vector<JobNode> JobNode::children(const std::string& key) const {
  std::vector<JobNode> out;
  const nlohmann::json* value = lookup(key);
  if (value == nullptr) return out;
  if (!value->is_array()) fail(key, std::string("expected an array, got ") + value->type_name());
  const std::string pointer = key_pointer(key);
  m_state->used.insert(pointer);
  for (std::size_t i = 0; i < value->size(); ++i) {
    if (!(*value)[i].is_object()) {
      fail(key + "/" + std::to_string(i), std::string("expected an object, got ") + (*value)[i].type_name());
    }
    const std::string item = pointer + "/" + std::to_string(i);
    m_state->used.insert(item);
    m_state->resolved[nlohmann::json::json_pointer(item)] = nlohmann::json::object();
    out.push_back(JobNode(m_state, item));
  }
  return out;
}

}  // namespace forensim
