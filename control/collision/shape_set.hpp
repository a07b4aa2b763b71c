// The collision shapes of one model, by link name (docs/collision.md, "Geometry files"), and the
// link pairs its SRDF disables. Owns the hull vertices its shapes point to, so shapes stay valid
// while the set lives (and when the set is moved). Built at set-up (host-side: allocates).
#pragma once

#include <Eigen/Core>

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "collision/shape.hpp"
#include "collision/srdf.hpp"

namespace mrqp::collision {

struct LinkShapes {
  std::string link;
  std::vector<Shape> shapes;
};

class ShapeSet {
 public:
  /// Adds a shape to `link` (created on first use). A hull's vertices are copied into the set.
  void add(const std::string& link, const Shape& shape,
           const std::vector<Eigen::Vector3d>& hull_vertices = {});
  void disable(const std::string& a, const std::string& b) { disabled_.insert(linkPair(a, b)); }

  const std::vector<LinkShapes>& links() const noexcept { return links_; }
  /// Shapes of `link`, nullptr when it has none.
  const LinkShapes* find(const std::string& link) const noexcept;
  bool disabled(const std::string& a, const std::string& b) const {
    return disabled_.count(linkPair(a, b)) != 0;
  }
  const std::set<LinkPair>& disabledPairs() const noexcept { return disabled_; }

 private:
  std::vector<LinkShapes> links_;
  std::vector<std::unique_ptr<std::vector<Eigen::Vector3d>>> hulls_;
  std::set<LinkPair> disabled_;
};

}  // namespace mrqp::collision
