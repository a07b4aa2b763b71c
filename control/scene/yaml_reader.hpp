// The checker every YAML reader of mrqp shares (scene files, the hardware and plant sections of a
// scene, the drive emulator's configuration): typed access to values with range checks, maps with
// a fixed set of keys, distinct names. Every failure throws SceneError
// "FILE:LINE: FIELD: message" (FIELD the dotted path of the key, e.g. "tasks[2].weight").
// Host-side: allocates and throws.
#pragma once

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <initializer_list>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene_spec.hpp"
#include "scene/scene_yaml.hpp"

namespace mrqp::scene {

inline std::string child(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

/// Names for an error message that lists the valid ones: "a, b, c", or "none".
inline std::string nameList(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

inline std::string item(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

inline int lineOf(const YAML::Node& n) {
  const YAML::Mark m = n.Mark();
  return m.is_null() ? 1 : m.line + 1;
}

inline std::optional<double> toDouble(const YAML::Node& n) {
  if (!n.IsScalar()) {
    return std::nullopt;
  }
  try {
    return n.as<double>();
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

inline std::optional<long long> toInteger(const YAML::Node& n) {
  if (!n.IsScalar()) {
    return std::nullopt;
  }
  try {
    return n.as<long long>();
  } catch (const YAML::Exception&) {
    return std::nullopt;
  }
}

/// A number too large for a double, which yaml-cpp does not convert.
inline bool isOverflow(const YAML::Node& n) {
  if (!n.IsScalar() || n.Scalar().empty()) {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(n.Scalar().c_str(), &end);
  return *end == '\0' && errno == ERANGE && std::isinf(v);
}

/// How a value is shown after "got": numbers as written, other text quoted.
inline std::string describe(const YAML::Node& n) {
  if (n.IsNull()) {
    return "null";
  }
  if (n.IsSequence()) {
    return "a list of " + std::to_string(n.size());
  }
  if (n.IsMap()) {
    return "a map";
  }
  return toDouble(n) || isOverflow(n) ? n.Scalar() : "\"" + n.Scalar() + "\"";
}

inline std::string formatNumber(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

enum class Bound { Any, NonNegative, Positive };

inline std::string expectedNumber(Bound b) {
  switch (b) {
    case Bound::NonNegative:
      return "a number >= 0";
    case Bound::Positive:
      return "a number > 0";
    case Bound::Any:
      break;
  }
  return "a number";
}

struct Entry {
  std::string key;
  YAML::Node key_node;
  YAML::Node value;
};

/// Typed access to YAML values; every failure throws SceneError naming file, line and field.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  Source source(const YAML::Node& n) const { return Source{file_, lineOf(n)}; }

  [[noreturn]] void fail(int line, const std::string& field, const std::string& message) const {
    throw SceneError(file_ + ":" + std::to_string(line) + ": " +
                     (field.empty() ? std::string("(top level)") : field) + ": " + message);
  }
  [[noreturn]] void fail(const YAML::Node& at, const std::string& field, const std::string& message) const {
    fail(lineOf(at), field, message);
  }

  double number(const YAML::Node& n, const std::string& field, Bound b = Bound::Any) const {
    const std::optional<double> v = toDouble(n);
    if ((v && !std::isfinite(*v)) || isOverflow(n)) {
      fail(n, field, "expected a finite number, got " + describe(n));
    }
    if (!v || (b == Bound::NonNegative && !(*v >= 0.0)) || (b == Bound::Positive && !(*v > 0.0))) {
      fail(n, field, "expected " + expectedNumber(b) + ", got " + describe(n));
    }
    return *v;
  }

  int integer(const YAML::Node& n, const std::string& field, int lo, int hi = INT_MAX) const {
    const std::optional<long long> v = toInteger(n);
    if (!v || *v < lo || *v > hi) {
      const std::string expected =
          lo == 0 && hi == 1 ? "0 or 1"
          : hi == INT_MAX    ? "an integer >= " + std::to_string(lo)
                             : "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
      fail(n, field, "expected " + expected + ", got " + describe(n));
    }
    return static_cast<int>(*v);
  }

  bool boolean(const YAML::Node& n, const std::string& field) const {
    if (n.IsScalar()) {
      try {
        return n.as<bool>();
      } catch (const YAML::Exception&) {}
    }
    fail(n, field, "expected true or false, got " + describe(n));
  }

  std::string name(const YAML::Node& n, const std::string& field) const {
    if (!n.IsScalar() || n.Scalar().empty()) {
      fail(n, field, "expected a name, got " + describe(n));
    }
    return n.Scalar();
  }

  Eigen::VectorXd numbers(const YAML::Node& n, const std::string& field, int size) const {
    if (!n.IsSequence() || static_cast<int>(n.size()) != size) {
      fail(n, field,
           "expected a list of " + std::to_string(size) + (size == 1 ? " number" : " numbers") + ", got " +
               describe(n));
    }
    Eigen::VectorXd v(size);
    for (int i = 0; i < size; ++i) {
      v(i) = number(n[static_cast<std::size_t>(i)], item(field, static_cast<std::size_t>(i)));
    }
    return v;
  }

  Eigen::Vector3d vec3(const YAML::Node& n, const std::string& field) const { return numbers(n, field, 3); }

  /// The items of a list; null reads as an empty list.
  std::vector<YAML::Node> list(const YAML::Node& n, const std::string& field) const {
    if (n.IsNull()) {
      return {};
    }
    if (!n.IsSequence()) {
      fail(n, field, "expected a list, got " + describe(n));
    }
    std::vector<YAML::Node> out;
    for (auto it = n.begin(); it != n.end(); ++it) {
      out.push_back(*it);
    }
    return out;
  }

  /// A list of distinct names.
  std::vector<std::string> names(const YAML::Node& n, const std::string& field) const {
    std::vector<std::string> out;
    const std::vector<YAML::Node> items = list(n, field);
    for (std::size_t i = 0; i < items.size(); ++i) {
      std::string s = name(items[i], item(field, i));
      if (std::find(out.begin(), out.end(), s) != out.end()) {
        fail(items[i], item(field, i), "'" + s + "' is listed twice");
      }
      out.push_back(std::move(s));
    }
    return out;
  }

  /// The entries of a map in file order; null reads as an empty map. Keys must be distinct.
  std::vector<Entry> entries(const YAML::Node& n, const std::string& field) const {
    if (n.IsNull()) {
      return {};
    }
    if (!n.IsMap()) {
      fail(n, field, "expected a map, got " + describe(n));
    }
    std::vector<Entry> out;
    for (auto it = n.begin(); it != n.end(); ++it) {
      const YAML::Node key = it->first;
      if (!key.IsScalar()) {
        fail(key, field, "expected a name as key, got " + describe(key));
      }
      for (const Entry& e : out) {
        if (e.key == key.Scalar()) {
          fail(key, child(field, e.key),
               "duplicate key (first at line " + std::to_string(lineOf(e.key_node)) + ")");
        }
      }
      out.push_back(Entry{key.Scalar(), key, it->second});
    }
    return out;
  }

  /// A map of names to numbers (initial joint positions, posture targets).
  std::map<std::string, double> numberMap(const YAML::Node& n, const std::string& field) const {
    std::map<std::string, double> out;
    for (const Entry& e : entries(n, field)) {
      out[e.key] = number(e.value, child(field, e.key));
    }
    return out;
  }

 private:
  std::string file_;
};

/// A YAML map with a fixed set of allowed keys: any other key is an error.
class Map {
 public:
  Map(const Reader& r, const YAML::Node& n, std::string path, std::initializer_list<const char*> keys)
      : r_(r), node_(n), path_(std::move(path)), entries_(r.entries(n, path_)) {
    checkKeys(keys.begin(), keys.end());
  }
  /// The same with the allowed keys assembled at run time (e.g. from a registry).
  Map(const Reader& r, const YAML::Node& n, std::string path, const std::vector<std::string>& keys)
      : r_(r), node_(n), path_(std::move(path)), entries_(r.entries(n, path_)) {
    checkKeys(keys.begin(), keys.end());
  }

  const Reader& reader() const { return r_; }
  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  const std::vector<Entry>& entries() const { return entries_; }
  std::string at(const std::string& key) const { return child(path_, key); }
  Source source() const { return r_.source(node_); }

  const YAML::Node* find(const std::string& key) const {
    for (const Entry& e : entries_) {
      if (e.key == key) {
        return &e.value;
      }
    }
    return nullptr;
  }
  const Entry* entry(const std::string& key) const {
    for (const Entry& e : entries_) {
      if (e.key == key) {
        return &e;
      }
    }
    return nullptr;
  }
  bool has(const std::string& key) const { return find(key) != nullptr; }

  const YAML::Node& require(const std::string& key) const {
    const YAML::Node* n = find(key);
    if (n == nullptr) {
      r_.fail(node_, path_, "missing required field '" + key + "'");
    }
    return *n;
  }

  std::string name(const std::string& key) const { return r_.name(require(key), at(key)); }
  double number(const std::string& key, Bound b, double fallback) const {
    const YAML::Node* n = find(key);
    return n != nullptr ? r_.number(*n, at(key), b) : fallback;
  }
  int integer(const std::string& key, int lo, int hi, int fallback) const {
    const YAML::Node* n = find(key);
    return n != nullptr ? r_.integer(*n, at(key), lo, hi) : fallback;
  }
  bool boolean(const std::string& key, bool fallback) const {
    const YAML::Node* n = find(key);
    return n != nullptr ? r_.boolean(*n, at(key)) : fallback;
  }
  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback) const {
    const YAML::Node* n = find(key);
    return n != nullptr ? r_.vec3(*n, at(key)) : fallback;
  }

  /// Rejects `key` when it is present: `why` says why it does not apply here.
  void forbid(const std::string& key, const std::string& why) const {
    if (const Entry* e = entry(key)) {
      r_.fail(e->key_node, at(key), why);
    }
  }

 private:
  template <class It>
  void checkKeys(It first, It last) const {
    for (const Entry& e : entries_) {
      const bool known = std::any_of(first, last, [&](const auto& k) { return e.key == k; });
      if (!known) {
        r_.fail(e.key_node, at(e.key), "unknown key");
      }
    }
  }

  const Reader& r_;
  YAML::Node node_;
  std::string path_;
  std::vector<Entry> entries_;
};

/// Names must be distinct within one kind of element (entities, contacts, tasks, ...).
class UniqueNames {
 public:
  UniqueNames(const Reader& r, const char* what) : r_(r), what_(what) {}
  void add(const std::string& name, const YAML::Node& at, const std::string& field) {
    const auto [it, inserted] = lines_.emplace(name, lineOf(at));
    if (!inserted) {
      r_.fail(at, field,
              "duplicate " + what_ + " '" + name + "' (first at line " + std::to_string(it->second) + ")");
    }
  }

 private:
  const Reader& r_;
  std::string what_;
  std::map<std::string, int> lines_;
};

/// Largest YAML file readTextFile reads by default (scene, hardware, plant, timeline, drive
/// emulator files), bytes: a real one is a few kilobytes (docs/robustness.md).
constexpr std::size_t kMaxYamlFileBytes = std::size_t{4} << 20;

/// Parses one YAML document held in `text` (a second document is an error); syntax errors become
/// SceneError "FILE:LINE: yaml: message". Never yaml-cpp's LoadAll, which loops allocating on
/// input such as "[]," (yaml_reader.cpp): the documents are counted from parser events first.
YAML::Node parseYamlDocument(const std::string& text, const std::string& file_name_for_messages);

/// Reads a whole file of at most `max_bytes` (errors "FILE: cannot open: reason", "FILE: too
/// large: ..." for a larger file or an endless device such as /dev/zero).
std::string readTextFile(const std::string& path, std::size_t max_bytes = kMaxYamlFileBytes);

/// Rethrows a yaml-cpp exception as SceneError "FILE:LINE: yaml: message".
[[noreturn]] void yamlError(const std::string& file, const YAML::Exception& e);

}  // namespace mrqp::scene
