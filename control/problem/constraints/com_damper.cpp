// CoM support-region damper (paper 2, eq. 7): support polygon and rows; see com_damper.hpp.
#include "problem/constraints/com_damper.hpp"

#include <algorithm>

#include "problem/multi_robot_problem.hpp"

namespace mrqp::problem {

ComDamper::ComDamper(int entity, double interaction, double security, double damping)
    : entity_(entity), interaction_(interaction), security_(security), damping_(damping) {}

const char* ComDamper::check(const MultiRobotProblem& p) const noexcept {
  if (entity_ < 0 || entity_ >= p.entityCount() || !(interaction_ > security_) || !(security_ >= 0.0) ||
      !(damping_ > 0.0)) {
    return "a CoM damper needs an entity, interaction > security ≥ 0 and damping > 0";
  }
  return nullptr;
}

void ComDamper::update(const MultiRobotProblem& p, ConstraintRows& out) noexcept {
  const double dt = p.settings().dt;
  const Entity& e = p.entity(entity_);
  const int o = p.velocityOffset(entity_);
  polygon_.clear();
  for (int id = 0; id < p.contactCapacity(); ++id) {
    if (!p.contactActive(id)) continue;
    const ContactDesc& c = p.contact(id);
    if (c.entity != entity_ || c.other_entity >= 0) continue;
    const Pose sf = e.framePose(c.frame);
    for (int i = 0; i < c.npoints; ++i) polygon_.add(sf.R * c.points[static_cast<std::size_t>(i)] + sf.p);
  }
  polygon_.build();
  const Eigen::Vector2d cxy = e.com().head<2>();
  Eigen::Vector3d cv;
  cv.noalias() = e.comJacobian() * e.v();
  const Eigen::Vector2d vxy = cv.head<2>();
  const int edges = std::min(polygon_.edges(), kRows);
  for (int i = 0; i < edges; ++i) {
    const double d = polygon_.distance(i, cxy);
    if (d >= interaction_) continue;  // row stays free (l = −inf)
    const Eigen::Vector2d a = polygon_.normal(i);
    out.C.block(i, o, 1, e.nv()).noalias() = dt * a.transpose() * e.comJacobian().topRows<2>();
    out.l(i) = -damping_ * (d - security_) / (interaction_ - security_) - a.dot(vxy) -
               dt * a.dot(e.comBias().head<2>());
  }
}

}  // namespace mrqp::problem
