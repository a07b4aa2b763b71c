#include "mesh_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <optional>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <unordered_set>
#include <utility>

namespace mrqp::gen {
namespace {

namespace fs = std::filesystem;

// Internal error carrying the <problem> part of MeshReadResult::error.
struct MeshError {
  std::string problem;
};

[[noreturn]] void fail(std::string problem) { throw MeshError{std::move(problem)}; }

// ---- small text helpers --------------------------------------------------------------

bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

bool equalsNoCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

bool startsWith(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && s.compare(0, prefix.size(), prefix) == 0;
}

// A token for messages: shortened and with control bytes replaced.
std::string quoteToken(std::string_view tok) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < tok.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(tok[i]);
    out += (c < 0x20 || c == 0x7f) ? '?' : static_cast<char>(c);
  }
  if (tok.size() > kMax) out += "...";
  out += "'";
  return out;
}

// Locale-independent parse of a whole token as a double (a leading '+' is accepted).
bool parseDouble(std::string_view tok, double& out) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b != e && *b == '+') ++b;
  if (b == e) return false;
  const auto res = std::from_chars(b, e, out);
  return res.ec == std::errc() && res.ptr == e;
}

bool parseUnsigned(std::string_view tok, std::uint64_t& out) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b == e) return false;
  const auto res = std::from_chars(b, e, out);
  return res.ec == std::errc() && res.ptr == e;
}

// Splits on whitespace, calling f(token, byte offset of the token).
template <class F>
void forEachToken(std::string_view s, F&& f) {
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && isSpace(s[i])) ++i;
    const std::size_t b = i;
    while (i < s.size() && !isSpace(s[i])) ++i;
    if (i > b) f(s.substr(b, i - b), b);
  }
}

// ---- distinct vertex collection -------------------------------------------------------

class VertexSet {
 public:
  void add(const Eigen::Vector3d& p) {
    Key k{};
    for (int i = 0; i < 3; ++i) {
      const double v = p[i] == 0.0 ? 0.0 : p[i];  // -0.0 and 0.0 are the same position
      std::memcpy(&k.bits[static_cast<std::size_t>(i)], &v, sizeof v);
    }
    if (seen_.insert(k).second) points_.push_back(p);
  }
  std::vector<Eigen::Vector3d> take() { return std::move(points_); }
  bool empty() const { return points_.empty(); }

 private:
  struct Key {
    std::uint64_t bits[3];
    bool operator==(const Key& o) const {
      return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
  };
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0x9e3779b97f4a7c15ULL;
      for (const std::uint64_t b : k.bits) {
        h ^= b + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
      }
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_set<Key, KeyHash> seen_;
  std::vector<Eigen::Vector3d> points_;
};

// ---- 4x4 transforms -------------------------------------------------------------------

// Row-major affine transforms, multiplied in a fixed order so that the vertices read do not
// depend on how the library was compiled (Eigen may vectorise products differently).
struct Mat4 {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  double& operator()(int r, int c) { return m[static_cast<std::size_t>(4 * r + c)]; }
  double operator()(int r, int c) const { return m[static_cast<std::size_t>(4 * r + c)]; }

  Mat4 operator*(const Mat4& o) const {
    Mat4 p;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        p(r, c) = (*this)(r, 0) * o(0, c) + (*this)(r, 1) * o(1, c) + (*this)(r, 2) * o(2, c) +
                  (*this)(r, 3) * o(3, c);
      }
    }
    return p;
  }

  // The affine part applied to a point (a projective bottom row is ignored).
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const {
    Eigen::Vector3d y;
    for (int r = 0; r < 3; ++r) {
      y[r] = (*this)(r, 0) * x[0] + (*this)(r, 1) * x[1] + (*this)(r, 2) * x[2] + (*this)(r, 3);
    }
    return y;
  }

  static Mat4 rowMajor(const std::vector<double>& v) {
    Mat4 t;
    std::copy(v.begin(), v.begin() + 16, t.m.begin());
    return t;
  }

  // Rotation by `degrees` about (x, y, z) (need not be unit; zero gives the identity).
  static Mat4 rotation(double x, double y, double z, double degrees) {
    Mat4 t;
    const double len = std::sqrt(x * x + y * y + z * z);
    if (!(len > 0.0)) return t;
    x /= len;
    y /= len;
    z /= len;
    constexpr double kPi = 3.14159265358979323846;
    const double a = degrees * kPi / 180.0;
    const double c = std::cos(a);
    const double s = std::sin(a);
    const double k = 1.0 - c;
    t(0, 0) = c + x * x * k;
    t(0, 1) = x * y * k - z * s;
    t(0, 2) = x * z * k + y * s;
    t(1, 0) = y * x * k + z * s;
    t(1, 1) = c + y * y * k;
    t(1, 2) = y * z * k - x * s;
    t(2, 0) = z * x * k - y * s;
    t(2, 1) = z * y * k + x * s;
    t(2, 2) = c + z * z * k;
    return t;
  }
};

// ---- STL ------------------------------------------------------------------------------

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
        fail("malformed binary STL: non-finite vertex coordinate in triangle " +
             std::to_string(t));
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
    fail("truncated binary STL: " + std::to_string(size) +
         " bytes, shorter than the 84-byte header" + note);
  }
  const std::string sizes = "the header declares " + std::to_string(count) +
                            " triangles, i.e. 84 + 50*" + std::to_string(count) + " = " +
                            std::to_string(expected) + " bytes, but the file has " +
                            std::to_string(size) + " bytes" + note;
  if (size < expected) fail("truncated binary STL: " + sizes);
  fail("binary STL size mismatch: " + sizes);
}

// ---- OBJ ------------------------------------------------------------------------------

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
    forEachToken(text, [&](std::string_view t, std::size_t) { toks.push_back(t); });
    if (toks.empty() || toks[0] != "v") continue;
    if (toks.size() < 4) {
      fail("malformed OBJ: vertex with fewer than 3 coordinates at line " + std::to_string(line));
    }
    Eigen::Vector3d x;
    for (int k = 0; k < 3; ++k) {
      const std::string_view num = toks[static_cast<std::size_t>(k) + 1];
      if (!parseDouble(num, x[k]) || !std::isfinite(x[k])) {
        fail("malformed OBJ: bad vertex coordinate " + quoteToken(num) + " at line " +
             std::to_string(line));
      }
    }
    out.add(x);
  }
}

// ---- minimal XML ----------------------------------------------------------------------

struct XmlElement {
  std::string name;     // local name, without a namespace prefix
  std::string rawName;  // as written, for matching the closing tag
  std::vector<std::pair<std::string, std::string>> attrs;
  std::string text;  // all character data directly inside, concatenated
  std::vector<std::size_t> children;
  std::size_t parent = std::numeric_limits<std::size_t>::max();

  const std::string* attr(std::string_view n) const {
    for (const auto& a : attrs) {
      if (a.first == n) return &a.second;
    }
    return nullptr;
  }
};

class XmlDocument {
 public:
  explicit XmlDocument(const std::string& s) : s_(s) { parse(); }
  const XmlElement& operator[](std::size_t i) const { return elems_[i]; }
  std::size_t size() const { return elems_.size(); }

 private:
  [[noreturn]] void error(std::size_t offset, const std::string& what) const {
    const auto end = s_.begin() + static_cast<std::ptrdiff_t>(std::min(offset, s_.size()));
    const auto line = 1 + std::count(s_.begin(), end, '\n');
    fail("malformed XML: " + what + " at line " + std::to_string(line));
  }

  static bool isNameChar(char c) {
    const auto u = static_cast<unsigned char>(c);
    return std::isalnum(u) != 0 || c == '_' || c == ':' || c == '-' || c == '.' || u >= 0x80;
  }

  std::string readName(std::size_t& k) const {
    const std::size_t b = k;
    while (k < s_.size() && isNameChar(s_[k])) ++k;
    return s_.substr(b, k - b);
  }

  void skipSpace(std::size_t& k) const {
    while (k < s_.size() && isSpace(s_[k])) ++k;
  }

  static void appendUtf8(std::string& out, unsigned long cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | ((cp >> 18) & 0x07));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  // Appends `in` with the predefined and numeric character references decoded; an
  // unknown reference is kept as written.
  static void appendDecoded(std::string& out, std::string_view in) {
    std::size_t i = 0;
    while (i < in.size()) {
      const std::size_t amp = in.find('&', i);
      if (amp == std::string_view::npos) {
        out.append(in.substr(i));
        return;
      }
      out.append(in.substr(i, amp - i));
      const std::size_t semi = in.find(';', amp);
      if (semi == std::string_view::npos || semi - amp > 12) {
        out += '&';
        i = amp + 1;
        continue;
      }
      const std::string_view ent = in.substr(amp + 1, semi - amp - 1);
      if (ent == "lt") out += '<';
      else if (ent == "gt") out += '>';
      else if (ent == "amp") out += '&';
      else if (ent == "quot") out += '"';
      else if (ent == "apos") out += '\'';
      else if (ent.size() > 1 && ent[0] == '#') {
        unsigned long cp = 0;
        const bool hex = ent[1] == 'x' || ent[1] == 'X';
        const char* b = ent.data() + (hex ? 2 : 1);
        const char* e = ent.data() + ent.size();
        const auto res = std::from_chars(b, e, cp, hex ? 16 : 10);
        if (res.ec == std::errc() && res.ptr == e && b != e && cp <= 0x10FFFF) {
          appendUtf8(out, cp);
        } else {
          out.append(in.substr(amp, semi - amp + 1));
        }
      } else {
        out.append(in.substr(amp, semi - amp + 1));
      }
      i = semi + 1;
    }
  }

  void parse() {
    const std::size_t n = s_.size();
    std::size_t i = startsWith(s_, "\xEF\xBB\xBF") ? 3 : 0;  // UTF-8 byte order mark
    std::vector<std::size_t> open;
    bool rootClosed = false;
    auto find = [&](std::string_view what, std::size_t from, const char* construct) {
      const std::size_t e = s_.find(what, from);
      if (e == std::string::npos) error(from, std::string("unterminated ") + construct);
      return e;
    };
    while (i < n) {
      if (s_[i] != '<') {
        std::size_t j = s_.find('<', i);
        if (j == std::string::npos) j = n;
        const std::string_view text(s_.data() + i, j - i);
        if (open.empty()) {
          if (!std::all_of(text.begin(), text.end(), isSpace)) {
            error(i, "text outside the root element");
          }
        } else {
          appendDecoded(elems_[open.back()].text, text);
        }
        i = j;
        continue;
      }
      const std::string_view rest(s_.data() + i, n - i);
      if (startsWith(rest, "<?")) {
        i = find("?>", i + 2, "processing instruction") + 2;
      } else if (startsWith(rest, "<!--")) {
        i = find("-->", i + 4, "comment") + 3;
      } else if (startsWith(rest, "<![CDATA[")) {
        const std::size_t e = find("]]>", i + 9, "CDATA section");
        if (open.empty()) error(i, "CDATA outside the root element");
        elems_[open.back()].text.append(s_, i + 9, e - (i + 9));
        i = e + 3;
      } else if (startsWith(rest, "<!")) {  // <!DOCTYPE ...>, possibly with [ ... ]
        int depth = 0;
        std::size_t k = i + 2;
        for (; k < n; ++k) {
          if (s_[k] == '[') ++depth;
          else if (s_[k] == ']') --depth;
          else if (s_[k] == '>' && depth <= 0) break;
        }
        if (k >= n) error(i, "unterminated <!...> declaration");
        i = k + 1;
      } else if (startsWith(rest, "</")) {
        std::size_t k = i + 2;
        const std::string name = readName(k);
        skipSpace(k);
        if (k >= n || s_[k] != '>') error(i, "invalid closing tag");
        if (open.empty()) error(i, "closing tag </" + name + "> without an open element");
        if (elems_[open.back()].rawName != name) {
          error(i, "closing tag </" + name + "> does not match <" + elems_[open.back()].rawName + ">");
        }
        open.pop_back();
        if (open.empty()) rootClosed = true;
        i = k + 1;
      } else {
        if (rootClosed || (open.empty() && !elems_.empty())) error(i, "second root element");
        std::size_t k = i + 1;
        XmlElement el;
        el.rawName = readName(k);
        if (el.rawName.empty()) error(i, "invalid tag");
        const std::size_t colon = el.rawName.rfind(':');
        el.name = colon == std::string::npos ? el.rawName : el.rawName.substr(colon + 1);
        bool selfClosing = false;
        for (;;) {
          skipSpace(k);
          if (k >= n) error(i, "unterminated tag <" + el.rawName + ">");
          if (s_[k] == '>') {
            ++k;
            break;
          }
          if (s_[k] == '/' && k + 1 < n && s_[k + 1] == '>') {
            k += 2;
            selfClosing = true;
            break;
          }
          std::string attrName = readName(k);
          if (attrName.empty()) error(k, "invalid attribute in <" + el.rawName + ">");
          skipSpace(k);
          if (k >= n || s_[k] != '=') error(k, "attribute '" + attrName + "' without a value");
          ++k;
          skipSpace(k);
          if (k >= n || (s_[k] != '"' && s_[k] != '\'')) {
            error(k, "unquoted value of attribute '" + attrName + "'");
          }
          const std::size_t close = s_.find(s_[k], k + 1);
          if (close == std::string::npos) error(k, "unterminated value of attribute '" + attrName + "'");
          std::string value;
          appendDecoded(value, std::string_view(s_.data() + k + 1, close - k - 1));
          el.attrs.emplace_back(std::move(attrName), std::move(value));
          k = close + 1;
        }
        const std::size_t index = elems_.size();
        if (!open.empty()) {
          el.parent = open.back();
          elems_[open.back()].children.push_back(index);
        }
        elems_.push_back(std::move(el));
        if (!selfClosing) open.push_back(index);
        else if (open.empty()) rootClosed = true;
        i = k;
      }
    }
    if (!open.empty()) {
      error(n, "unexpected end of file inside <" + elems_[open.back()].rawName + ">");
    }
    if (elems_.empty()) error(n, "no root element");
  }

  const std::string& s_;
  std::vector<XmlElement> elems_;
};

// ---- COLLADA --------------------------------------------------------------------------

class ColladaReader {
 public:
  explicit ColladaReader(const XmlDocument& doc) : doc_(doc) {
    for (std::size_t i = 0; i < doc_.size(); ++i) {
      if (const std::string* id = doc_[i].attr("id")) ids_.emplace(*id, i);  // first wins
    }
  }

  void read(VertexSet& out) {
    const XmlElement& root = doc_[0];
    if (root.name != "COLLADA") {
      fail("malformed COLLADA: the root element is <" + root.rawName + ">, not <COLLADA>");
    }
    double meter = 1.0;
    if (const auto asset = child(0, "asset")) {
      if (const auto unit = child(*asset, "unit")) {
        if (const std::string* m = doc_[*unit].attr("meter")) {
          if (!parseDouble(*m, meter) || !std::isfinite(meter) || meter <= 0.0) {
            fail("malformed COLLADA: invalid <unit meter=" + quoteToken(*m) + ">");
          }
        }
      }
    }
    unit_ = meter;

    if (const auto scene = visualScene()) {
      for (const std::size_t c : doc_[*scene].children) {
        if (doc_[c].name == "node") visitNode(c, Mat4{}, 0, out);
      }
    }
    if (instanced_ == 0) {  // no scene, or it instantiates no mesh: every mesh as stored
      for (std::size_t i = 0; i < doc_.size(); ++i) {
        if (doc_[i].name != "geometry") continue;
        if (const auto mesh = child(i, "mesh")) addMesh(*mesh, Mat4{}, out);
      }
    }
  }

 private:
  static constexpr int kMaxNodeDepth = 256;

  std::optional<std::size_t> child(std::size_t parent, std::string_view name) const {
    for (const std::size_t c : doc_[parent].children) {
      if (doc_[c].name == name) return c;
    }
    return std::nullopt;
  }

  std::string describe(std::size_t e) const {
    std::string d = "<" + doc_[e].name;
    if (const std::string* id = doc_[e].attr("id")) d += " id='" + *id + "'";
    else if (const std::string* nm = doc_[e].attr("name")) d += " name='" + *nm + "'";
    return d + ">";
  }

  // The element named by a "#id" reference held in attribute `attr` of element `from`.
  std::size_t resolve(std::size_t from, const char* attr, std::string_view expected) const {
    const std::string* ref = doc_[from].attr(attr);
    if (ref == nullptr) fail("malformed COLLADA: " + describe(from) + " without a '" + attr + "' attribute");
    if (ref->empty() || (*ref)[0] != '#') {
      fail("unsupported COLLADA: external reference '" + *ref + "' in " + describe(from));
    }
    const auto it = ids_.find(ref->substr(1));
    if (it == ids_.end()) fail("malformed COLLADA: " + describe(from) + " refers to missing '" + *ref + "'");
    if (doc_[it->second].name != expected) {
      fail("malformed COLLADA: '" + *ref + "' in " + describe(from) + " is a <" +
           doc_[it->second].name + ">, not a <" + std::string(expected) + ">");
    }
    return it->second;
  }

  std::vector<double> numbers(std::size_t e) const {
    std::vector<double> v;
    forEachToken(doc_[e].text, [&](std::string_view tok, std::size_t) {
      double x = 0.0;
      if (!parseDouble(tok, x) || !std::isfinite(x)) {
        fail("malformed COLLADA: bad number " + quoteToken(tok) + " in " + describe(e));
      }
      v.push_back(x);
    });
    return v;
  }

  std::vector<double> numbers(std::size_t e, std::size_t expected, std::size_t node) const {
    std::vector<double> v = numbers(e);
    if (v.size() != expected) {
      fail("malformed COLLADA: <" + doc_[e].name + "> in " + describe(node) + " has " +
           std::to_string(v.size()) + " numbers, expected " + std::to_string(expected));
    }
    return v;
  }

  std::size_t sizeAttr(std::size_t e, const char* name, std::size_t fallback) const {
    const std::string* a = doc_[e].attr(name);
    if (a == nullptr) return fallback;
    std::uint64_t v = 0;
    if (!parseUnsigned(*a, v) || v > std::numeric_limits<std::uint32_t>::max()) {
      fail("malformed COLLADA: invalid " + std::string(name) + "=" + quoteToken(*a) + " in " + describe(e));
    }
    return static_cast<std::size_t>(v);
  }

  std::optional<std::size_t> visualScene() const {
    if (const auto scene = child(0, "scene")) {
      if (const auto ivs = child(*scene, "instance_visual_scene")) {
        return resolve(*ivs, "url", "visual_scene");
      }
    }
    if (const auto lib = child(0, "library_visual_scenes")) return child(*lib, "visual_scene");
    return std::nullopt;
  }

  Mat4 localTransform(std::size_t node) const {
    Mat4 t;
    for (const std::size_t c : doc_[node].children) {
      const std::string& n = doc_[c].name;
      Mat4 m;
      if (n == "matrix") {
        m = Mat4::rowMajor(numbers(c, 16, node));
      } else if (n == "translate") {
        const std::vector<double> v = numbers(c, 3, node);
        m(0, 3) = v[0];
        m(1, 3) = v[1];
        m(2, 3) = v[2];
      } else if (n == "rotate") {
        const std::vector<double> v = numbers(c, 4, node);
        m = Mat4::rotation(v[0], v[1], v[2], v[3]);
      } else if (n == "scale") {
        const std::vector<double> v = numbers(c, 3, node);
        m(0, 0) = v[0];
        m(1, 1) = v[1];
        m(2, 2) = v[2];
      } else if (n == "lookat" || n == "skew") {
        fail("unsupported COLLADA: <" + n + "> transform in " + describe(node));
      } else {
        continue;
      }
      t = t * m;
    }
    return t;
  }

  void visitNode(std::size_t node, const Mat4& parent, int depth, VertexSet& out) {
    if (depth > kMaxNodeDepth) {
      fail("unsupported COLLADA: nodes nested deeper than " + std::to_string(kMaxNodeDepth) +
           " (an <instance_node> cycle?) at " + describe(node));
    }
    const Mat4 t = parent * localTransform(node);
    for (const std::size_t c : doc_[node].children) {
      const std::string& n = doc_[c].name;
      if (n == "node") {
        visitNode(c, t, depth + 1, out);
      } else if (n == "instance_node") {
        visitNode(resolve(c, "url", "node"), t, depth + 1, out);
      } else if (n == "instance_geometry") {
        const std::size_t geometry = resolve(c, "url", "geometry");
        if (const auto mesh = child(geometry, "mesh")) addMesh(*mesh, t, out);
      } else if (n == "instance_controller") {
        const std::size_t controller = resolve(c, "url", "controller");
        const auto skin = child(controller, "skin");
        if (!skin) continue;  // morph controllers are not read
        const std::size_t geometry = resolve(*skin, "source", "geometry");
        Mat4 bind;
        if (const auto bsm = child(*skin, "bind_shape_matrix")) bind = Mat4::rowMajor(numbers(*bsm, 16, *skin));
        if (const auto mesh = child(geometry, "mesh")) addMesh(*mesh, t * bind, out);
      }
    }
  }

  void addMesh(std::size_t mesh, const Mat4& t, VertexSet& out) {
    const std::size_t geometry = doc_[mesh].parent;
    const std::string where = "the <mesh> of " + describe(geometry);
    const auto vertices = child(mesh, "vertices");
    if (!vertices) fail("malformed COLLADA: " + where + " has no <vertices>");
    std::optional<std::size_t> input;
    for (const std::size_t c : doc_[*vertices].children) {
      const std::string* sem = doc_[c].attr("semantic");
      if (doc_[c].name == "input" && sem != nullptr && *sem == "POSITION") input = c;
    }
    if (!input) fail("malformed COLLADA: " + where + " has no <input semantic=\"POSITION\">");
    const std::size_t source = resolve(*input, "source", "source");
    const auto array = child(source, "float_array");
    if (!array) fail("malformed COLLADA: position " + describe(source) + " has no <float_array>");
    const std::vector<double> values = numbers(*array);
    const std::size_t declared = sizeAttr(*array, "count", values.size());
    if (values.size() < declared) {
      fail("malformed COLLADA: " + describe(*array) + " declares " + std::to_string(declared) +
           " values but holds " + std::to_string(values.size()));
    }
    std::size_t stride = 3;
    std::size_t offset = 0;
    std::size_t count = 0;
    std::optional<std::size_t> accessor;
    if (const auto tc = child(source, "technique_common")) accessor = child(*tc, "accessor");
    if (accessor) {
      std::size_t params = 0;
      for (const std::size_t c : doc_[*accessor].children) if (doc_[c].name == "param") ++params;
      stride = sizeAttr(*accessor, "stride", std::max<std::size_t>(params, 3));
      offset = sizeAttr(*accessor, "offset", 0);
    }
    if (stride < 3) {
      fail("unsupported COLLADA: position accessor stride " + std::to_string(stride) + " < 3 in " + where);
    }
    const std::size_t available = declared > offset ? (declared - offset + stride - 3) / stride : 0;
    count = accessor ? sizeAttr(*accessor, "count", available) : available;
    if (count > available) {
      fail("malformed COLLADA: the position accessor of " + where + " reads " + std::to_string(count) +
           " points but " + describe(*array) + " holds " + std::to_string(declared) + " values");
    }
    for (std::size_t p = 0; p < count; ++p) {
      const std::size_t b = offset + p * stride;
      const Eigen::Vector3d x(values[b], values[b + 1], values[b + 2]);
      const Eigen::Vector3d y = unit_ * t.apply(x);
      if (!y.allFinite()) fail("malformed COLLADA: non-finite transformed vertex in " + where);
      out.add(y);
    }
    ++instanced_;
  }

  const XmlDocument& doc_;
  std::unordered_map<std::string, std::size_t> ids_;
  double unit_ = 1.0;
  std::size_t instanced_ = 0;
};

void readDae(const std::string& data, VertexSet& out) {
  const XmlDocument doc(data);
  ColladaReader(doc).read(out);
}

// ---- URI helpers ----------------------------------------------------------------------

bool isRegularFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::vector<std::string> envPathList(const char* name) {
  std::vector<std::string> dirs;
  const char* v = std::getenv(name);
  if (v == nullptr) return dirs;
  const std::string_view s(v);
  std::size_t b = 0;
  while (b <= s.size()) {
    std::size_t e = s.find(':', b);
    if (e == std::string_view::npos) e = s.size();
    if (e > b) dirs.emplace_back(s.substr(b, e - b));
    b = e + 1;
  }
  return dirs;
}

std::string percentDecode(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    unsigned value = 0;
    if (s[i] == '%' && i + 2 < s.size()) {
      const auto res = std::from_chars(s.data() + i + 1, s.data() + i + 3, value, 16);
      if (res.ec == std::errc() && res.ptr == s.data() + i + 3) {
        out += static_cast<char>(value);
        i += 2;
        continue;
      }
    }
    out += s[i];
  }
  return out;
}

fs::path normalised(const fs::path& p) { return p.lexically_normal(); }

}  // namespace

MeshReadResult readMeshVertices(const std::string& path) {
  MeshReadResult result;
  auto failed = [&](const std::string& problem) {
    result.ok = false;
    result.error = "mesh '" + path + "': " + problem;
    result.vertices.clear();
    return result;
  };
  try {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (path.empty() || !fs::exists(st)) return failed("file not found");
    if (!fs::is_regular_file(st)) return failed("not a regular file");

    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), lower);
    if (ext != ".stl" && ext != ".obj" && ext != ".dae") {
      return failed(ext.empty() ? "unsupported mesh format (no file extension; supported: .stl, .obj, .dae)"
                                : "unsupported mesh format '" + ext + "' (supported: .stl, .obj, .dae)");
    }

    std::ifstream in(path, std::ios::binary);
    if (!in) return failed("cannot open file");
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0) return failed("cannot read file");
    in.seekg(0, std::ios::beg);
    std::string data(static_cast<std::size_t>(size), '\0');
    if (size > 0 && !in.read(data.data(), size)) return failed("cannot read file");

    VertexSet vertices;
    if (ext == ".stl") readStl(data, vertices);
    else if (ext == ".obj") readObj(data, vertices);
    else readDae(data, vertices);
    if (vertices.empty()) return failed("no vertices");
    result.ok = true;
    result.vertices = vertices.take();
    return result;
  } catch (const MeshError& e) {
    return failed(e.problem);
  } catch (const std::bad_alloc&) {
    return failed("out of memory");
  } catch (const std::exception& e) {
    return failed(std::string("cannot read file (") + e.what() + ")");
  }
}

std::string resolveMeshUri(const std::string& uri, const std::string& urdf_dir,
                           const std::vector<std::string>& package_paths) {
  constexpr std::string_view kPackage = "package://";
  constexpr std::string_view kFile = "file://";
  if (uri.empty()) return {};

  if (startsWith(uri, kPackage)) {
    const std::string rest = uri.substr(kPackage.size());
    const std::size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) return {};
    const std::string pkg = rest.substr(0, slash);
    const std::size_t relBegin = rest.find_first_not_of('/', slash);
    if (relBegin == std::string::npos) return {};
    const std::string rel = rest.substr(relBegin);
    std::vector<std::string> dirs = package_paths;
    for (std::string& d : envPathList("ROS_PACKAGE_PATH")) dirs.push_back(std::move(d));
    for (const std::string& d : dirs) {
      if (d.empty()) continue;
      fs::path base = fs::path(d).lexically_normal();
      if (const fs::path c = normalised(base / pkg / rel); isRegularFile(c)) return c.string();
      if (base.filename().empty()) base = base.parent_path();  // "dir/" -> "dir"
      if (base.filename() == pkg) {
        if (const fs::path c = normalised(base / rel); isRegularFile(c)) return c.string();
      }
    }
    for (const std::string& prefix : envPathList("AMENT_PREFIX_PATH")) {
      if (const fs::path c = normalised(fs::path(prefix) / "share" / pkg / rel); isRegularFile(c)) {
        return c.string();
      }
    }
    return {};
  }

  std::string local;
  if (startsWith(uri, kFile)) {
    std::string_view rest = std::string_view(uri).substr(kFile.size());
    if (startsWith(rest, "localhost/")) rest.remove_prefix(std::string_view("localhost").size());
    local = percentDecode(rest);
  } else {
    const std::size_t colon = uri.find("://");
    if (colon != std::string::npos && colon > 0 &&
        std::all_of(uri.begin(), uri.begin() + static_cast<std::ptrdiff_t>(colon), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '+' || c == '-' || c == '.';
        })) {
      return {};  // another scheme (http://, model://, ...)
    }
    local = uri;
  }
  if (local.empty()) return {};
  fs::path p(local);
  if (p.is_relative() && !urdf_dir.empty()) p = fs::path(urdf_dir) / p;
  p = p.lexically_normal();  // "urdf/../meshes/x.stl" need not have an existing "urdf"
  return isRegularFile(p) ? p.string() : std::string();
}

}  // namespace mrqp::gen
