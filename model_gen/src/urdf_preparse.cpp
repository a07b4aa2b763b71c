// URDF checks before urdfdom parses, and the canonical text it parses (urdf_preparse.hpp).
#include "urdf_preparse.hpp"

#include <cstdio>
#include <utility>
#include <vector>

#include "generator_limits.hpp"
#include "mesh_format.hpp"
#include "name_rule.hpp"
#include "urdf_loader.hpp"
#include "xml_document.hpp"

namespace mrqp::gen {
namespace {

using mesh::XmlDocument;
using mesh::XmlElement;

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw ModelError(source + ": " + what);
}

std::string at(std::size_t line) { return " at line " + std::to_string(line); }

/// "<link name='x'>" for messages (the name made printable).
std::string describe(const XmlElement& e) {
  std::string d = "<" + printable(e.rawName, 40);
  if (const std::string* n = e.attr("name")) d += " name='" + printable(*n, 40) + "'";
  return d + ">";
}

/// Bytes XML 1.0 does not allow anywhere in a document (tab, newline and return are allowed).
void checkControlCharacters(const std::string& xml, const std::string& source) {
  std::size_t line = 1;
  for (const char ch : xml) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\n') ++line;
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", static_cast<unsigned>(c));
      fail(source, std::string("control character ") + hex + " (not allowed in XML)" + at(line));
    }
  }
}

void appendEscaped(std::string& out, const std::string& value, const XmlElement& e,
                   const std::string& source) {
  for (const char ch : value) {
    const auto c = static_cast<unsigned char>(ch);
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        if (c == 0) fail(source, describe(e) + ": a NUL character reference" + at(e.line));
        if (c < 0x20)
          out += "&#" + std::to_string(static_cast<unsigned>(c)) + ";";
        else
          out += ch;
    }
  }
}

void checkCounts(const XmlDocument& doc, const std::string& source) {
  const XmlElement& robot = doc[0];
  std::size_t links = 0, joints = 0, collisions = 0;
  for (const std::size_t c : robot.children) {
    const XmlElement& e = doc[c];
    if (e.rawName == "link") {
      if (++links > kMaxLinks)
        fail(source, describe(e) + ": more than " + std::to_string(kMaxLinks) +
                         " <link> elements (the link limit)" + at(e.line));
      for (const std::size_t g : e.children) {
        if (doc[g].rawName == "collision" && ++collisions > kMaxCollisions)
          fail(source, describe(e) + ": more than " + std::to_string(kMaxCollisions) +
                           " <collision> elements in the robot (the collision limit)" + at(doc[g].line));
      }
    } else if (e.rawName == "joint" && ++joints > kMaxJoints) {
      fail(source, describe(e) + ": more than " + std::to_string(kMaxJoints) +
                       " <joint> elements (the joint limit)" + at(e.line));
    }
  }
}

/// The document written back, iteratively (no recursion on the nesting).
std::string serialise(const XmlDocument& doc, const std::string& source, std::size_t size_hint) {
  std::string out;
  out.reserve(size_hint);
  std::vector<std::pair<std::size_t, std::size_t>> stack;  // element, next child
  auto open = [&](std::size_t i) {
    const XmlElement& e = doc[i];
    out += '<';
    out += e.rawName;
    for (const auto& [name, value] : e.attrs) {
      out += ' ';
      out += name;
      out += "=\"";
      appendEscaped(out, value, e, source);
      out += '"';
    }
    out += '>';
    appendEscaped(out, e.text, e, source);
    stack.emplace_back(i, 0);
  };
  open(0);
  while (!stack.empty()) {
    auto& [i, next] = stack.back();
    const XmlElement& e = doc[i];
    if (next < e.children.size()) {
      const std::size_t child = e.children[next++];
      open(child);  // may reallocate the stack: `i` and `next` are not used after this
      continue;
    }
    out += "</";
    out += e.rawName;
    out += ">\n";
    stack.pop_back();
  }
  return out;
}

}  // namespace

std::string canonicalUrdf(const std::string& xml, const std::string& source) {
  if (xml.size() > kMaxUrdfBytes)
    fail(source, "larger than the " + std::to_string(kMaxUrdfBytes) + "-byte URDF limit (" +
                     std::to_string(xml.size()) + " bytes)");
  checkControlCharacters(xml, source);
  try {
    const XmlDocument doc(xml, mesh::XmlLimits{kMaxUrdfDepth, kMaxUrdfNodes});
    checkCounts(doc, source);
    return serialise(doc, source, xml.size());
  } catch (const mesh::MeshError& e) {
    if (e.problem.rfind("malformed XML", 0) != 0) fail(source, e.problem);  // a limit
    // worded as urdfdom words a document it cannot read; text that does not even start with a tag
    // is not XML
    const std::size_t first = xml.find_first_not_of(" \t\r\n");
    const bool tag = first != std::string::npos && xml[first] == '<';
    fail(source,
         "URDF parse error: " + e.problem + (tag ? "" : "; no <robot> element (not an XML URDF document)"));
  }
}

}  // namespace mrqp::gen
