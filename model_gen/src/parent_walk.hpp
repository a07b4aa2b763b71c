// The cycle check of the URDF loader: links given by their parent link (each at most one), found
// on a cycle or not in one walk up per link that stops where an earlier walk stopped, so the work
// is linear in the number of links (a 10,000-link chain is 10,000 steps, not 50 million).
#pragma once

#include <cstddef>
#include <vector>

namespace mrqp::gen {

/// `parent[i]` is the parent of node i, -1 for a root. Walks up from node 0, 1, ... in turn and
/// returns the first node met twice on one walk (a node on a cycle), or -1 when every walk ends
/// at a root. Each parent link is followed at most twice over all walks (once walking, once marking
/// the walk settled); `steps`, when given, receives how many links were followed in all.
int firstNodeOnCycle(const std::vector<int>& parent, std::size_t* steps = nullptr);

}  // namespace mrqp::gen
