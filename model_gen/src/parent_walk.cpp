// Linear cycle check over parent links (parent_walk.hpp).
#include "parent_walk.hpp"

#include <cstdint>

namespace mrqp::gen {

int firstNodeOnCycle(const std::vector<int>& parent, std::size_t* steps) {
  enum : std::uint8_t { kUnseen, kOnWalk, kDone };
  std::vector<std::uint8_t> state(parent.size(), kUnseen);
  std::size_t followed = 0;
  int found = -1;
  for (std::size_t start = 0; start < parent.size() && found < 0; ++start) {
    // Mark the walk, stop at a root, at a node an earlier walk settled, or at a node of this walk.
    int cur = static_cast<int>(start);
    while (cur >= 0 && state[static_cast<std::size_t>(cur)] == kUnseen) {
      state[static_cast<std::size_t>(cur)] = kOnWalk;
      cur = parent[static_cast<std::size_t>(cur)];
      if (cur >= 0) ++followed;
    }
    if (cur >= 0 && state[static_cast<std::size_t>(cur)] == kOnWalk) found = cur;
    // Settle this walk's nodes (walk it again: every node on it is kOnWalk until settled).
    for (int n = static_cast<int>(start); n >= 0 && state[static_cast<std::size_t>(n)] == kOnWalk;
         n = parent[static_cast<std::size_t>(n)]) {
      state[static_cast<std::size_t>(n)] = kDone;
      ++followed;
    }
  }
  if (steps) *steps = followed;
  return found;
}

}  // namespace mrqp::gen
