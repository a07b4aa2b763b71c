// Members added to a written summary.json (see summary_fields.hpp).
#include "summary_fields.hpp"

#include <fstream>
#include <sstream>

namespace mrqp::run {

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
