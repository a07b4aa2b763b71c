// Wavefront OBJ meshes: the vertex lines "v x y z [w]".
#include "mesh_format.hpp"
#include "text_tokens.hpp"

#include <cmath>
#include <cstring>
#include <string_view>

namespace mrqp::gen::mesh {

void readObj(const std::string& data, VertexSet& out) {
  const std::string_view s(data);
  std::size_t pos = 0;
  std::size_t line = 0;
  std::vector<std::string_view> toks;
  while (pos < s.size()) {
    std::size_t eol = s.find('\n', pos);
    if (eol == std::string_view::npos) eol = s.size();
    std::string_view text = s.substr(pos, eol - pos);
    pos = eol + 1;
    ++line;
    if (const std::size_t hash = text.find('#'); hash != std::string_view::npos) {
      text = text.substr(0, hash);
    }
    toks.clear();
    forEachToken(text, [&](std::string_view t, std::size_t) {
      if (toks.size() < 4) toks.push_back(t);  // "v x y z": the rest of a line is not needed
    });
    if (toks.empty() || toks[0] != "v") continue;
    if (toks.size() < 4) {
      fail("malformed OBJ: vertex with fewer than 3 coordinates at line " + std::to_string(line));
    }
    Eigen::Vector3d x;
    for (int k = 0; k < 3; ++k) {
      const std::string_view num = toks[static_cast<std::size_t>(k) + 1];
      if (!parseDouble(num, x[k]) || !std::isfinite(x[k])) {
        fail("malformed OBJ: bad vertex coordinate " + quoteToken(num) + " at line " + std::to_string(line));
      }
    }
    out.add(x);
  }
}

}  // namespace mrqp::gen::mesh
