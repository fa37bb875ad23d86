#pragma once
/// Job files: the plain JSON description of a run (a mummification, a wound timeline, a reconstruction).
/// The CLI, the server and the tests load them through this one loader. Reading is tracked key by key
/// (after pbrt-v4's parameter lists): when a run has read what it needs, check_all_used() reports any key
/// nobody read, with its JSON path and the nearest known key, so a typo is an error, not a silent default.
/// Every value read, defaults included, is recorded in resolved(), which the run folder stores.

#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"

namespace forensim {

class JobNode;

/// A parsed job file. Owns the JSON, the record of keys read and the resolved job.
class JobDocument {
 public:
  /// Parses JSON text; `source` names it in errors (a path or "command line"). Throws JobError with the
  /// line and column of a syntax error.
  static JobDocument parse(const std::string& text, const std::string& source);
  /// Reads and parses a file. Throws IoError if it cannot be read.
  static JobDocument load(const std::filesystem::path& path);
  /// An empty job (every value takes its default).
  static JobDocument empty(const std::string& source = "built-in defaults");

  /// The root object.
  JobNode root();
  /// Throws JobError naming the first key (depth-first, in file order) that was never read.
  void check_all_used() const;
  /// The job as run: every key read, with defaults filled in.
  const nlohmann::json& resolved() const { return m_state->resolved; }
  const std::string& source() const { return m_state->source; }

 private:
  friend class JobNode;
  struct State {
    std::string source;
    nlohmann::json json;
    nlohmann::json resolved = nlohmann::json::object();
    std::set<std::string> used;  // JSON pointers of keys read (objects count as used when a child is read)
  };
  std::shared_ptr<State> m_state;
};

/// One JSON object inside a job, addressed by its JSON pointer.
class JobNode {
 public:
  /// True when the key is present (marks nothing as used).
  bool has(const std::string& key) const;
  /// Value of `key` or `fallback` when absent; throws JobError on a wrong type.
  template <typename T>
  T get(const std::string& key, const T& fallback) const {
    const nlohmann::json* value = lookup(key);
    if (value == nullptr) {
      record(key, nlohmann::json(fallback));
      return fallback;
    }
    T out = convert<T>(*value, key);
    record(key, *value);
    return out;
  }
  /// Value of `key`; throws JobError when absent or of the wrong type.
  template <typename T>
  T require(const std::string& key) const {
    const nlohmann::json* value = lookup(key);
    if (value == nullptr) fail(key, "required key is missing");
    T out = convert<T>(*value, key);
    record(key, *value);
    return out;
  }
  /// Number in [lo, hi] (inclusive), or `fallback` when absent. Rejects NaN and infinities.
  double get_number(const std::string& key, double fallback, double lo, double hi) const;
  /// Integer in [lo, hi], or `fallback` when absent.
  long long get_integer(const std::string& key, long long fallback, long long lo, long long hi) const;
  /// String that must be one of `choices`, or `fallback` when absent.
  std::string get_choice(const std::string& key, const std::string& fallback,
                         const std::vector<std::string>& choices) const;
  /// Child object (an empty one when absent, so its defaults apply). Throws if present but not an object.
  JobNode child(const std::string& key) const;
  /// Array of objects under `key` (empty when absent).
  std::vector<JobNode> children(const std::string& key) const;
  /// This node's JSON pointer ("" for the root).
  const std::string& path() const { return m_pointer; }
  /// Throws JobError(source, path/key, problem).
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

 private:
  friend class JobDocument;
  JobNode(std::shared_ptr<JobDocument::State> state, std::string pointer)
      : m_state(std::move(state)), m_pointer(std::move(pointer)) {}
  const nlohmann::json* lookup(const std::string& key) const;
  void record(const std::string& key, const nlohmann::json& value) const;
  std::string key_pointer(const std::string& key) const;
  template <typename T>
  T convert(const nlohmann::json& value, const std::string& key) const {
    try {
      if constexpr (std::is_floating_point_v<T>) {
        if (!value.is_number()) fail(key, std::string("expected a number, got ") + value.type_name());
      } else if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
        if (!value.is_number_integer()) fail(key, std::string("expected an integer, got ") + value.type_name());
      } else if constexpr (std::is_same_v<T, bool>) {
        if (!value.is_boolean()) fail(key, std::string("expected true or false, got ") + value.type_name());
      } else if constexpr (std::is_same_v<T, std::string>) {
        if (!value.is_string()) fail(key, std::string("expected a string, got ") + value.type_name());
      }
      return value.get<T>();
    } catch (const nlohmann::json::exception& e) {
      fail(key, std::string("wrong type: ") + e.what());
    }
  }
  std::shared_ptr<JobDocument::State> m_state;
  std::string m_pointer;
};

/// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace forensim
