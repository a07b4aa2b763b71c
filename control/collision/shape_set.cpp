// The collision shapes of one model by link; see shape_set.hpp.
#include "collision/shape_set.hpp"

namespace mrqp::collision {

void ShapeSet::add(const std::string& link, const Shape& shape, const std::vector<Eigen::Vector3d>& hull) {
  LinkShapes* ls = nullptr;
  for (LinkShapes& l : links_) {
    if (l.link == link) ls = &l;
  }
  if (ls == nullptr) {
    links_.push_back(LinkShapes{link, {}});
    ls = &links_.back();
  }
  Shape s = shape;
  if (s.kind == ShapeKind::Hull) {
    hulls_.push_back(std::make_unique<std::vector<Eigen::Vector3d>>(hull));
    const std::vector<Eigen::Vector3d>& v = *hulls_.back();
    const Shape h = makeHull(v.data(), static_cast<int>(v.size()));
    s.vertices = h.vertices;
    s.nvertices = h.nvertices;
    s.centre = h.centre;
  }
  ls->shapes.push_back(s);
}

const LinkShapes* ShapeSet::find(const std::string& link) const noexcept {
  for (const LinkShapes& l : links_) {
    if (l.link == link) return &l;
  }
  return nullptr;
}

}  // namespace mrqp::collision
