// The URDF text checked and rewritten before urdfdom sees it. urdfdom parses with TinyXML, which
// recurses once per nesting level (100,000 nested elements overflow the stack), and builds every
// link it reads: so the size, nesting and element counts are checked first, by the iterative XML
// reader of mrqp_mesh (xml_document.hpp), and urdfdom is given that reader's document written
// back canonically, which has exactly the nesting checked.
#pragma once

#include <string>

namespace mrqp::gen {

/// Checks `xml` (from the file or stream named `source` in messages) against the limits of
/// generator_limits.hpp: size, control characters (not allowed in XML), well-formed XML, nesting
/// depth, elements and attributes, <link>, <joint> and <collision> counts; throws ModelError
/// ("SOURCE: ... at line N" naming the element and the limit) on the first violation. Returns
/// the same document as elements, attributes and character data only (comments, declarations,
/// CDATA sections and DOCTYPE removed, text before the children of its element), every
/// attribute value and text escaped.
std::string canonicalUrdf(const std::string& xml, const std::string& source);

}  // namespace mrqp::gen
