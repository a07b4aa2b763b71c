// STL meshes, binary and ASCII (the rules that tell them apart: mesh_reader.hpp).
#include "mesh_format.hpp"
#include "text_tokens.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace mrqp::gen::mesh {

namespace {

constexpr std::size_t kStlHeaderBytes = 84;    // 80-byte header + uint32 triangle count
constexpr std::size_t kStlTriangleBytes = 50;  // normal, 3 vertices (float32 x 12), uint16

std::uint32_t readU32LE(const char* p) {
  const auto* u = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint32_t>(u[0]) | (static_cast<std::uint32_t>(u[1]) << 8) |
         (static_cast<std::uint32_t>(u[2]) << 16) | (static_cast<std::uint32_t>(u[3]) << 24);
}

float readF32LE(const char* p) {
  const std::uint32_t bits = readU32LE(p);
  float f = 0.0F;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

void readBinaryStl(const std::string& data, std::uint32_t count, VertexSet& out) {
  for (std::uint32_t t = 0; t < count; ++t) {
    const char* tri = data.data() + kStlHeaderBytes + std::size_t{t} * kStlTriangleBytes;
    for (int v = 0; v < 3; ++v) {
      const char* p = tri + 12 + 12 * v;
      const Eigen::Vector3d x(readF32LE(p), readF32LE(p + 4), readF32LE(p + 8));
      if (!x.allFinite()) {
        fail("malformed binary STL: non-finite vertex coordinate in triangle " + std::to_string(t));
      }
      out.add(x);
    }
  }
}

bool startsWithSolidKeyword(const std::string& data) {
  std::size_t i = 0;
  while (i < data.size() && isSpace(data[i])) ++i;
  if (data.size() - i < 5 || !equalsNoCase(std::string_view(data).substr(i, 5), "solid")) {
    return false;
  }
  return data.size() == i + 5 || isSpace(data[i + 5]);
}

bool looksLikeText(const std::string& data) {
  return std::none_of(data.begin(), data.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u == 0 || (u < 0x20 && !isSpace(c));
  });
}

void readAsciiStl(const std::string& data, VertexSet& out) {
  const std::string_view s(data);
  std::size_t i = 0;
  std::size_t line = 1;
  // Next whitespace-separated token on any line; empty at end of file.
  auto next = [&]() -> std::string_view {
    while (i < s.size() && isSpace(s[i])) {
      if (s[i] == '\n') ++line;
      ++i;
    }
    const std::size_t b = i;
    while (i < s.size() && !isSpace(s[i])) ++i;
    return s.substr(b, i - b);
  };
  auto skipRestOfLine = [&]() {
    while (i < s.size() && s[i] != '\n') ++i;
  };
  auto at = [&]() { return " at line " + std::to_string(line); };

  bool inSolid = false;
  bool inLoop = false;
  int loopVertices = 0;
  for (std::string_view tok = next(); !tok.empty(); tok = next()) {
    if (equalsNoCase(tok, "solid")) {
      if (inSolid) fail("malformed ASCII STL: 'solid' inside a solid" + at());
      inSolid = true;
      skipRestOfLine();  // the solid's name
    } else if (equalsNoCase(tok, "endsolid")) {
      if (!inSolid || inLoop) fail("malformed ASCII STL: unexpected 'endsolid'" + at());
      inSolid = false;
      skipRestOfLine();
    } else if (!inSolid) {
      fail("malformed ASCII STL: " + quoteToken(tok) + " outside 'solid ... endsolid'" + at());
    } else if (equalsNoCase(tok, "loop")) {
      if (inLoop) fail("malformed ASCII STL: nested 'loop'" + at());
      inLoop = true;
      loopVertices = 0;
    } else if (equalsNoCase(tok, "endloop")) {
      if (!inLoop || loopVertices != 3) {
        fail("malformed ASCII STL: facet loop with " + std::to_string(loopVertices) +
             " vertices (expected 3)" + at());
      }
      inLoop = false;
    } else if (equalsNoCase(tok, "vertex")) {
      if (!inLoop) fail("malformed ASCII STL: 'vertex' outside 'outer loop'" + at());
      Eigen::Vector3d x;
      for (int k = 0; k < 3; ++k) {
        const std::size_t tokenLine = line;
        const std::string_view num = next();
        if (num.empty()) fail("truncated ASCII STL: incomplete vertex at line " + std::to_string(tokenLine));
        if (!parseDouble(num, x[k]) || !std::isfinite(x[k])) {
          fail("malformed ASCII STL: bad vertex coordinate " + quoteToken(num) + at());
        }
      }
      ++loopVertices;
      out.add(x);
    }
    // "facet", "normal" and its numbers, "outer", "endfacet": nothing to check.
  }
  if (inSolid) fail("truncated ASCII STL: missing 'endsolid' at the end of the file");
}

}  // namespace

void readStl(const std::string& data, VertexSet& out) {
  const std::size_t size = data.size();
  std::uint32_t count = 0;
  std::uint64_t expected = 0;
  if (size >= kStlHeaderBytes) {
    count = readU32LE(data.data() + 80);
    expected = kStlHeaderBytes + std::uint64_t{count} * kStlTriangleBytes;
    if (expected == size) {  // binary, even when the header starts with "solid"
      readBinaryStl(data, count, out);
      return;
    }
  }
  if (startsWithSolidKeyword(data) && looksLikeText(data)) {
    readAsciiStl(data, out);
    return;
  }
  const std::string note =
      startsWithSolidKeyword(data) ? " (the header starts with \"solid\" but the file is not text)" : "";
  if (size < kStlHeaderBytes) {
    fail("truncated binary STL: " + std::to_string(size) + " bytes, shorter than the 84-byte header" + note);
  }
  const std::string sizes = "the header declares " + std::to_string(count) + " triangles, i.e. 84 + 50*" +
                            std::to_string(count) + " = " + std::to_string(expected) +
                            " bytes, but the file has " + std::to_string(size) + " bytes" + note;
  if (size < expected) fail("truncated binary STL: " + sizes);
  fail("binary STL size mismatch: " + sizes);
}

}  // namespace mrqp::gen::mesh
