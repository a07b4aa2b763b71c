// --set KEY=VALUE on a scene file (see scene_override.hpp).
#include "loop/scene_override.hpp"

#include <cctype>

#include "scene/yaml_reader.hpp"

namespace mrqp::loop {

namespace {

struct Segment {
  std::string key;
  bool indexed = false;
  std::string index;  // a number or an item name
};

std::vector<Segment> parsePath(const std::string& path, const std::string& file) {
  std::vector<Segment> out;
  std::size_t i = 0;
  auto bad = [&](const std::string& why) {
    throw scene::SceneError(file + ":1: " + path + ": --set: " + why);
  };
  while (i < path.size()) {
    Segment s;
    while (i < path.size() && path[i] != '.' && path[i] != '[') s.key += path[i++];
    if (s.key.empty()) bad("expected a key name at '" + path.substr(i) + "'");
    if (i < path.size() && path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string::npos) bad("missing ']'");
      s.indexed = true;
      s.index = path.substr(i + 1, close - i - 1);
      if (s.index.empty()) bad("empty index");
      i = close + 1;
    }
    if (i < path.size()) {
      if (path[i] != '.') bad("expected '.' after ']'");
      ++i;
    }
    out.push_back(s);
  }
  if (out.empty()) bad("empty path");
  return out;
}

bool isNumber(const std::string& s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

/// The extent [pos, end) of a one-line value in the text, or false.
bool valueExtent(const std::string& text, const YAML::Node& n, std::size_t* pos, std::size_t* end) {
  const YAML::Mark m = n.Mark();
  if (m.is_null() || m.pos < 0 || static_cast<std::size_t>(m.pos) >= text.size()) return false;
  std::size_t p = static_cast<std::size_t>(m.pos);
  const char c = text[p];
  std::size_t e = p;
  if (c == '[' || c == '{') {
    int depth = 0;
    for (; e < text.size(); ++e) {
      if (text[e] == '\n') return false;
      if (text[e] == '[' || text[e] == '{') ++depth;
      if (text[e] == ']' || text[e] == '}') {
        if (--depth == 0) {
          ++e;
          break;
        }
      }
    }
    if (depth != 0) return false;
  } else if (c == '"' || c == '\'') {
    e = text.find(c, p + 1);
    if (e == std::string::npos || text.find('\n', p) < e) return false;
    ++e;
  } else if (n.IsScalar()) {
    if (text.compare(p, n.Scalar().size(), n.Scalar()) != 0) return false;
    e = p + n.Scalar().size();
  } else {
    return false;
  }
  *pos = p;
  *end = e;
  return true;
}

}  // namespace

std::string applySceneOverride(const std::string& text, const std::string& file,
                               const std::string& assignment) {
  const std::size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw scene::SceneError(file + ":1: " + assignment + ": --set: expected KEY=VALUE");
  }
  const std::string path = assignment.substr(0, eq);
  const std::string value_text = assignment.substr(eq + 1);
  const YAML::Node value = scene::parseYamlDocument(value_text, "--set " + path);
  if (value_text.find('\n') != std::string::npos) {
    throw scene::SceneError(file + ":1: " + path + ": --set: the value must be on one line");
  }
  YAML::Node root = scene::parseYamlDocument(text, file);
  const std::vector<Segment> segs = parsePath(path, file);
  // YAML::Node assignment writes through to the node it refers to: rebind with reset().
  YAML::Node node;
  node.reset(root);
  std::string at;
  for (std::size_t k = 0; k < segs.size(); ++k) {
    const Segment& s = segs[k];
    const bool last = k + 1 == segs.size();
    if (!node.IsMap()) {
      scene::Reader(file).fail(node, at, "--set: not a map, cannot hold '" + s.key + "'");
    }
    at = scene::child(at, s.key);
    const YAML::Node next = node[s.key];
    if (!next) {
      if (last && !s.indexed) {
        node[s.key] = value;  // a new key: re-emit the scene
        YAML::Emitter out;
        out << root;
        return std::string(out.c_str()) + "\n";
      }
      scene::Reader(file).fail(node, at, "--set: no such key");
    }
    node.reset(next);
    if (s.indexed) {
      if (!node.IsSequence()) scene::Reader(file).fail(node, at, "--set: not a list");
      std::size_t idx = node.size();
      if (isNumber(s.index)) {
        idx = static_cast<std::size_t>(std::stoul(s.index));
      } else {
        for (std::size_t i = 0; i < node.size(); ++i) {
          if (node[i].IsMap() && node[i]["name"] && node[i]["name"].IsScalar() &&
              node[i]["name"].Scalar() == s.index) {
            idx = i;
          }
        }
      }
      if (idx >= node.size()) {
        scene::Reader(file).fail(
            node, at, "--set: no item [" + s.index + "] (the list has " + std::to_string(node.size()) + ")");
      }
      at = scene::item(at, idx);
      const YAML::Node element = node[idx];
      node.reset(element);
    }
  }
  std::size_t pos = 0, end = 0;
  if (valueExtent(text, node, &pos, &end)) {
    return text.substr(0, pos) + value_text + text.substr(end);
  }
  scene::Reader(file).fail(node, at, "--set: only a value written on one line can be replaced");
}

}  // namespace mrqp::loop
