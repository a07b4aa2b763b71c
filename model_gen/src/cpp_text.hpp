// Text read from a file (a URDF's names, the URDF's file name) written into generated C++: one
// function per context the generator writes such text into. Every one of them produces printable
// ASCII only, so no byte of the input can end a comment or a literal, start a new line, splice
// lines (a backslash before a newline) or form a trigraph; the names have also passed
// name_rule.hpp. Identifiers of the generated code never come from such text.
#pragma once

#include <string>
#include <string_view>

namespace mrqp::gen {

/// A C++ string literal, quotes included, whose value is exactly the bytes of `text`: printable
/// ASCII as it is but for `"`, `\` and `?` (escaped with a backslash), every other byte as a
/// three-digit octal escape (\ooo, which no following character can extend).
std::string cppStringLiteral(std::string_view text);

/// `text` made safe inside a C++ comment, `//` or `/* */`, for a reader: printable ASCII as it is
/// but for `\` (written \x5c, so no backslash can end a line), the `/` of "*/" and the `*` of "/*"
/// (\x2f and \x2a) and the second `?` of "??" (\x3f); every other byte as \xHH.
std::string cppCommentText(std::string_view text);

}  // namespace mrqp::gen
