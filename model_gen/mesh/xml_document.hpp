// A minimal XML reader (no external library) for COLLADA files and, before urdfdom parses them,
// URDF files (model_gen/src/urdf_preparse.cpp): elements with their local name, attributes,
// character data, children and line, in document order. Iterative (no recursion on the nesting),
// with limits on the nesting depth and on the number of elements and attributes. Errors throw
// MeshError: "malformed XML: ... at line N", or for a limit "<x> nested deeper than N levels at
// line L" / "more than N XML elements and attributes at line L".
#pragma once

#include "mesh_format.hpp"
#include "text_tokens.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <string_view>
#include <system_error>
#include <utility>

namespace mrqp::gen::mesh {

struct XmlElement {
  std::string name;     // local name, without a namespace prefix
  std::string rawName;  // as written, for matching the closing tag
  std::vector<std::pair<std::string, std::string>> attrs;
  std::string text;  // all character data directly inside, concatenated
  std::vector<std::size_t> children;
  std::size_t parent = std::numeric_limits<std::size_t>::max();
  std::size_t line = 0;  // of the start tag

  const std::string* attr(std::string_view n) const {
    for (const auto& a : attrs) {
      if (a.first == n) return &a.second;
    }
    return nullptr;
  }
};

/// The nesting depth (the root element is level 1) and the number of elements and attributes
/// together a document may have.
struct XmlLimits {
  int max_depth;
  std::size_t max_nodes;
};

class XmlDocument {
 public:
  XmlDocument(const std::string& s, XmlLimits limits) : s_(s), limits_(limits) { parse(); }
  const XmlElement& operator[](std::size_t i) const { return elems_[i]; }
  std::size_t size() const { return elems_.size(); }

 private:
  [[noreturn]] void error(std::size_t offset, const std::string& what) const {
    fail("malformed XML: " + what + " at line " + std::to_string(lineOf(offset)));
  }

  std::size_t lineOf(std::size_t offset) const {
    const auto end = s_.begin() + static_cast<std::ptrdiff_t>(std::min(offset, s_.size()));
    return 1 + static_cast<std::size_t>(std::count(s_.begin(), end, '\n'));
  }

  /// Line of `offset`, counted forward from the last call's offset (offsets only grow while parsing).
  std::size_t lineAt(std::size_t offset) {
    lineCount_ +=
        static_cast<std::size_t>(std::count(s_.begin() + static_cast<std::ptrdiff_t>(lineOffset_),
                                            s_.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
    lineOffset_ = offset;
    return lineCount_;
  }

  static std::string tag(const std::string& rawName) {
    std::string t = "<";
    for (std::size_t i = 0; i < rawName.size() && i < 40; ++i) {
      const auto c = static_cast<unsigned char>(rawName[i]);
      t += c < 0x20 || c >= 0x7F ? '?' : rawName[i];
    }
    return t + (rawName.size() > 40 ? "...>" : ">");
  }

  void countNode(std::size_t offset) {
    if (++nodes_ > limits_.max_nodes) {
      fail("more than " + std::to_string(limits_.max_nodes) + " XML elements and attributes at line " +
           std::to_string(lineOf(offset)));
    }
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
      if (ent == "lt")
        out += '<';
      else if (ent == "gt")
        out += '>';
      else if (ent == "amp")
        out += '&';
      else if (ent == "quot")
        out += '"';
      else if (ent == "apos")
        out += '\'';
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
          if (s_[k] == '[')
            ++depth;
          else if (s_[k] == ']')
            --depth;
          else if (s_[k] == '>' && depth <= 0)
            break;
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
          countNode(k);
          el.attrs.emplace_back(std::move(attrName), std::move(value));
          k = close + 1;
        }
        countNode(i);
        el.line = lineAt(i);
        if (static_cast<int>(open.size()) >= limits_.max_depth) {
          fail(tag(el.rawName) + " nested deeper than " + std::to_string(limits_.max_depth) +
               " levels at line " + std::to_string(el.line));
        }
        const std::size_t index = elems_.size();
        if (!open.empty()) {
          el.parent = open.back();
          elems_[open.back()].children.push_back(index);
        }
        elems_.push_back(std::move(el));
        if (!selfClosing)
          open.push_back(index);
        else if (open.empty())
          rootClosed = true;
        i = k;
      }
    }
    if (!open.empty()) {
      error(n, "unexpected end of file inside <" + elems_[open.back()].rawName + ">");
    }
    if (elems_.empty()) error(n, "no root element");
  }

  const std::string& s_;
  XmlLimits limits_;
  std::vector<XmlElement> elems_;
  std::size_t nodes_ = 0;
  std::size_t lineOffset_ = 0;
  std::size_t lineCount_ = 1;
};

}  // namespace mrqp::gen::mesh
