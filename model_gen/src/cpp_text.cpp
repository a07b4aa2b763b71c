// Escaping file text for the generated C++ (cpp_text.hpp).
#include "cpp_text.hpp"

#include <cstdio>

namespace mrqp::gen {
namespace {

bool printableAscii(unsigned char c) { return c >= 0x20 && c <= 0x7E; }

void appendEscape(std::string& out, const char* format, unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, format, static_cast<unsigned>(c));
  out += buf;
}

}  // namespace

std::string cppStringLiteral(std::string_view text) {
  std::string out = "\"";
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\' || c == '?') {
      out += '\\';
      out += ch;
    } else if (printableAscii(c)) {
      out += ch;
    } else {
      appendEscape(out, "\\%03o", c);
    }
  }
  return out + "\"";
}

std::string cppCommentText(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    const char prev = i > 0 ? text[i - 1] : '\0';
    const bool closesBlock = c == '/' && prev == '*';  // the '/' of "*/"
    const bool opensBlock = c == '*' && prev == '/';   // the '*' of "/*"
    const bool trigraph = c == '?' && prev == '?';     // the second '?' of "??"
    if (!printableAscii(c) || c == '\\' || closesBlock || opensBlock || trigraph)
      appendEscape(out, "\\x%02x", c);
    else
      out += static_cast<char>(c);
  }
  return out;
}

}  // namespace mrqp::gen
