// Members added to a written summary.json (see summary_fields.hpp).
#include "summary_fields.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace mrqp::run {

std::string jsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

bool appendSummaryFields(const std::string& path,
                         const std::vector<std::pair<std::string, std::string>>& fields) {
  std::string text;
  {
    std::ifstream in(path);
    if (!in) return false;
    std::ostringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  const std::size_t close = text.find_last_not_of(" \t\r\n");
  if (close == std::string::npos || text[close] != '}') return false;
  const std::size_t last = text.find_last_not_of(" \t\r\n", close == 0 ? 0 : close - 1);
  const bool empty = last == std::string::npos || text[last] == '{';
  std::string add;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    add += std::string(empty && i == 0 ? "" : ",") + "\n  \"" + fields[i].first + "\": " + fields[i].second;
  }
  text = text.substr(0, last == std::string::npos ? close : last + 1) + add + "\n}\n";
  std::ofstream out(path, std::ios::trunc);
  if (!out) return false;
  out << text;
  return static_cast<bool>(out.flush());
}

}  // namespace mrqp::run
