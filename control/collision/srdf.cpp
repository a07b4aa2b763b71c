// SRDF disable_collisions reader; see srdf.hpp. A plain scan for the one element it needs.
#include "collision/srdf.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mrqp::collision {

LinkPair linkPair(const std::string& a, const std::string& b) {
  return a <= b ? LinkPair{a, b} : LinkPair{b, a};
}

namespace {

int lineAt(const std::string& text, std::size_t pos) {
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
}

// The value of attribute `name` inside the element text `el`, "" when absent.
std::string attribute(const std::string& el, const std::string& name) {
  std::size_t pos = 0;
  while ((pos = el.find(name, pos)) != std::string::npos) {
    const bool starts = pos > 0 && (el[pos - 1] == ' ' || el[pos - 1] == '\t' || el[pos - 1] == '\n');
    std::size_t eq = pos + name.size();
    while (eq < el.size() && (el[eq] == ' ' || el[eq] == '\t')) ++eq;
    if (starts && eq < el.size() && el[eq] == '=') {
      std::size_t q = eq + 1;
      while (q < el.size() && (el[q] == ' ' || el[q] == '\t')) ++q;
      if (q < el.size() && (el[q] == '"' || el[q] == '\'')) {
        const std::size_t end = el.find(el[q], q + 1);
        if (end != std::string::npos) return el.substr(q + 1, end - q - 1);
      }
    }
    pos += name.size();
  }
  return "";
}

}  // namespace

std::set<LinkPair> readSrdfDisabledPairs(const std::string& text, const std::string& file) {
  std::set<LinkPair> out;
  const std::string tag = "<disable_collisions";
  std::size_t pos = 0;
  while ((pos = text.find(tag, pos)) != std::string::npos) {
    const std::size_t end = text.find('>', pos);
    if (end == std::string::npos) {
      throw std::runtime_error(file + ":" + std::to_string(lineAt(text, pos)) +
                               ": disable_collisions: the element is not closed");
    }
    const std::string el = text.substr(pos + tag.size(), end - pos - tag.size());
    const std::string a = attribute(el, "link1"), b = attribute(el, "link2");
    if (a.empty() || b.empty()) {
      throw std::runtime_error(file + ":" + std::to_string(lineAt(text, pos)) +
                               ": disable_collisions: expected the attributes link1 and link2");
    }
    out.insert(linkPair(a, b));
    pos = end;
  }
  return out;
}

std::set<LinkPair> readSrdfDisabledPairsFile(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot read");
  std::stringstream ss;
  ss << f.rdbuf();
  return readSrdfDisabledPairs(ss.str(), path);
}

}  // namespace mrqp::collision
