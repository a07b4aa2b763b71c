// The pairs of links an SRDF file (MoveIt's semantic robot description) disables:
// <disable_collisions link1="a" link2="b" reason="..."/>. Host-side: allocates and throws.
#pragma once

#include <set>
#include <string>
#include <utility>

namespace mrqp::collision {

/// An unordered pair of link names, stored with first ≤ second.
using LinkPair = std::pair<std::string, std::string>;
LinkPair linkPair(const std::string& a, const std::string& b);

/// The disabled pairs of the SRDF text `text` (read from `file`, for messages). Throws
/// std::runtime_error "FILE:LINE: disable_collisions: message" on an element without link1/link2.
std::set<LinkPair> readSrdfDisabledPairs(const std::string& text, const std::string& file);

/// The same, from a file; throws "FILE: cannot read" when it cannot be read.
std::set<LinkPair> readSrdfDisabledPairsFile(const std::string& path);

}  // namespace mrqp::collision
