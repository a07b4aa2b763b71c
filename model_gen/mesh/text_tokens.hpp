// Token helpers of the text mesh formats (ASCII STL, OBJ, the XML of COLLADA): whitespace,
// case-insensitive comparison, strict number parsing, token iteration, quoting a token in an
// error message. Internal to mrqp_mesh.
#pragma once

#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <system_error>

namespace mrqp::gen::mesh {

inline bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

inline char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }

inline bool equalsNoCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

inline bool startsWith(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && s.compare(0, prefix.size(), prefix) == 0;
}

// A token for messages: shortened and with control bytes replaced.
inline std::string quoteToken(std::string_view tok) {
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
inline bool parseDouble(std::string_view tok, double& out) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b != e && *b == '+') ++b;
  if (b == e) return false;
  const auto res = std::from_chars(b, e, out);
  return res.ec == std::errc() && res.ptr == e;
}

inline bool parseUnsigned(std::string_view tok, std::uint64_t& out) {
  const char* b = tok.data();
  const char* e = b + tok.size();
  if (b == e) return false;
  const auto res = std::from_chars(b, e, out);
  return res.ec == std::errc() && res.ptr == e;
}

// Splits on whitespace, calling f(token, byte offset of the token).
template <class F>
inline void forEachToken(std::string_view s, F&& f) {
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && isSpace(s[i])) ++i;
    const std::size_t b = i;
    while (i < s.size() && !isSpace(s[i])) ++i;
    if (i > b) f(s.substr(b, i - b), b);
  }
}

}  // namespace mrqp::gen::mesh
