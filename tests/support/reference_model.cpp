#include "reference_model.hpp"

#include <urdf_model/joint.h>
#include <urdf_model/link.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

namespace mrqp::test {

namespace {

using Vector6d = ReferenceModel::Vector6d;
using Pose = ReferenceModel::Pose;

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::Vector3d angular(const Vector6d& m) { return m.head<3>(); }
Eigen::Vector3d linear(const Vector6d& m) { return m.tail<3>(); }

Vector6d spatial(const Eigen::Vector3d& ang, const Eigen::Vector3d& lin) {
  Vector6d out;
  out << ang, lin;
  return out;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0.0, -w.z(), w.y(),  //
      w.z(), 0.0, -w.x(),   //
      -w.y(), w.x(), 0.0;
  return S;
}

// A motion vector given at (and in the axes of) the parent frame, re-expressed in the child frame
// whose pose in the parent frame is X.
Vector6d motionToChild(const Pose& X, const Vector6d& m_parent) {
  const Eigen::Vector3d w = angular(m_parent);
  const Eigen::Vector3d v_at_child = linear(m_parent) + w.cross(X.p);
  return spatial(X.R.transpose() * w, X.R.transpose() * v_at_child);
}

// A force vector (moment; force) given in the child frame, re-expressed in the parent frame.
Vector6d forceToParent(const Pose& X, const Vector6d& f_child) {
  const Eigen::Vector3d f = X.R * linear(f_child);
  const Eigen::Vector3d n = X.R * angular(f_child) + X.p.cross(f);
  return spatial(n, f);
}

// Spatial cross product for motion vectors: m1 x m2.
Vector6d crossMotion(const Vector6d& m1, const Vector6d& m2) {
  const Eigen::Vector3d w = angular(m1), v = linear(m1);
  return spatial(w.cross(angular(m2)), w.cross(linear(m2)) + v.cross(angular(m2)));
}

// Spatial cross product of a motion with a force: m x* f.
Vector6d crossForce(const Vector6d& m, const Vector6d& f) {
  const Eigen::Vector3d w = angular(m), v = linear(m);
  return spatial(w.cross(angular(f)) + v.cross(linear(f)), w.cross(linear(f)));
}

// Spatial inertia (mass m, CoM c, rotational inertia Ic about the CoM) times a motion, all in
// the same frame: f = m (v + w x c), n = Ic w + c x f.
Vector6d inertiaTimes(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& Ic, const Vector6d& motion) {
  const Eigen::Vector3d w = angular(motion), v = linear(motion);
  const Eigen::Vector3d f = m * (v + w.cross(c));
  const Eigen::Vector3d n = Ic * w + c.cross(f);
  return spatial(n, f);
}

Pose compose(const Pose& a, const Pose& b) {
  Pose out;
  out.R = a.R * b.R;
  out.p = a.p + a.R * b.p;
  return out;
}

Pose toPose(const urdf::Pose& u) {
  double x = 0.0, y = 0.0, z = 0.0, w = 1.0;
  u.rotation.getQuaternion(x, y, z, w);
  Pose out;
  out.R = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
  out.p = Eigen::Vector3d(u.position.x, u.position.y, u.position.z);
  return out;
}

bool finite(const Pose& p) { return p.R.allFinite() && p.p.allFinite(); }

const char* typeName(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FIXED:
      return "fixed";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    default:
      return "unknown";
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Construction
// ---------------------------------------------------------------------------------------------

ReferenceModel ReferenceModel::fromUrdf(const std::string& path, bool floating_base) {
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDFFile(path);
  if (!urdf) throw std::runtime_error("ReferenceModel: cannot read or parse URDF file '" + path + "'");
  const urdf::LinkConstSharedPtr root = urdf->getRoot();
  if (!root) throw std::runtime_error("ReferenceModel: URDF '" + path + "' has no root link");

  ReferenceModel model;
  model.floating_base_ = floating_base;

  // Depth-first pre-order, children sorted by joint name. Explicit stack of (link, parent index).
  struct Item {
    urdf::LinkConstSharedPtr link;
    int parent;
  };
  std::vector<Item> stack{{root, -1}};
  std::set<std::string> visited;
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const urdf::Link& ul = *item.link;
    if (!visited.insert(ul.name).second)
      throw std::runtime_error("ReferenceModel: link '" + ul.name + "' is reached twice (cycle)");

    Link link;
    link.name = ul.name;
    link.parent = item.parent;
    if (item.parent < 0) {
      link.type = JointType::Root;
    } else {
      const urdf::Joint& uj = *ul.parent_joint;
      link.joint_name = uj.name;
      link.origin = toPose(uj.parent_to_joint_origin_transform);
      if (!finite(link.origin))
        throw std::runtime_error("ReferenceModel: joint '" + uj.name + "': origin is not finite");
      switch (uj.type) {
        case urdf::Joint::FIXED:
          link.type = JointType::Fixed;
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
          link.type = JointType::Revolute;
          break;
        case urdf::Joint::PRISMATIC:
          link.type = JointType::Prismatic;
          break;
        default:
          throw std::runtime_error("ReferenceModel: joint '" + uj.name + "': type " + typeName(uj.type) +
                                   " is not supported");
      }
      if (link.type != JointType::Fixed) {
        const Eigen::Vector3d axis(uj.axis.x, uj.axis.y, uj.axis.z);
        if (!axis.allFinite())
          throw std::runtime_error("ReferenceModel: joint '" + uj.name + "': axis is not finite");
        if (axis.norm() == 0.0)
          throw std::runtime_error("ReferenceModel: joint '" + uj.name + "': axis is zero");
        link.axis = axis.normalized();
      }
    }
    if (ul.inertial) {
      const urdf::Inertial& in = *ul.inertial;
      const Pose frame = toPose(in.origin);
      Eigen::Matrix3d I;
      I << in.ixx, in.ixy, in.ixz,  //
          in.ixy, in.iyy, in.iyz,   //
          in.ixz, in.iyz, in.izz;
      if (!std::isfinite(in.mass) || !I.allFinite() || !finite(frame))
        throw std::runtime_error("ReferenceModel: link '" + ul.name + "': inertial is not finite");
      if (in.mass < 0.0) throw std::runtime_error("ReferenceModel: link '" + ul.name + "': negative mass");
      link.mass = in.mass;
      link.com = frame.p;
      link.inertia_com = frame.R * I * frame.R.transpose();
    }
    const int index = static_cast<int>(model.links_.size());
    model.links_.push_back(link);

    std::vector<urdf::JointSharedPtr> children = ul.child_joints;
    std::sort(children.begin(), children.end(),
              [](const urdf::JointSharedPtr& a, const urdf::JointSharedPtr& b) { return a->name < b->name; });
    // Push in reverse so that the lexicographically first child is popped first.
    for (auto it = children.rbegin(); it != children.rend(); ++it) {
      const urdf::LinkConstSharedPtr child = urdf->getLink((*it)->child_link_name);
      if (!child)
        throw std::runtime_error("ReferenceModel: joint '" + (*it)->name + "': unknown child link '" +
                                 (*it)->child_link_name + "'");
      stack.push_back({child, index});
    }
  }

  // Frames, full joint coordinates.
  std::map<std::string, int> full_index_of;  // moving joint name -> full index
  for (Link& link : model.links_) {
    model.frame_names_.push_back(link.name);
    if (link.type == JointType::Revolute || link.type == JointType::Prismatic) {
      link.full_index = static_cast<int>(model.full_joint_names_.size());
      full_index_of[link.joint_name] = link.full_index;
      model.full_joint_names_.push_back(link.joint_name);
    }
  }

  // Independent joints: moving joints without a mimic element, DFS order.
  std::map<std::string, int> independent_index_of;
  for (const std::string& name : model.full_joint_names_) {
    if (!urdf->getJoint(name)->mimic) {
      independent_index_of[name] = static_cast<int>(model.joint_names_.size());
      model.joint_names_.push_back(name);
    }
  }

  // Mimic map, resolving chains: q_j = mult * q_root + off.
  const int nfull = static_cast<int>(model.full_joint_names_.size());
  const int nj = static_cast<int>(model.joint_names_.size());
  model.mimic_G_ = Eigen::MatrixXd::Zero(nfull, nj);
  model.mimic_offset_ = Eigen::VectorXd::Zero(nfull);
  for (int i = 0; i < nfull; ++i) {
    const std::string& name = model.full_joint_names_[static_cast<std::size_t>(i)];
    double mult = 1.0, off = 0.0;
    std::string current = name;
    std::set<std::string> seen;
    while (true) {
      const urdf::JointConstSharedPtr joint = urdf->getJoint(current);
      if (!joint->mimic) break;
      if (!seen.insert(current).second)
        throw std::runtime_error("ReferenceModel: joint '" + name + "': mimic cycle through '" + current +
                                 "'");
      const urdf::JointMimic& mimic = *joint->mimic;
      if (!std::isfinite(mimic.multiplier) || !std::isfinite(mimic.offset))
        throw std::runtime_error("ReferenceModel: joint '" + current + "': mimic is not finite");
      if (!urdf->getJoint(mimic.joint_name))
        throw std::runtime_error("ReferenceModel: joint '" + current + "': mimic refers to unknown joint '" +
                                 mimic.joint_name + "'");
      if (full_index_of.count(mimic.joint_name) == 0)
        throw std::runtime_error("ReferenceModel: joint '" + current + "': mimic refers to joint '" +
                                 mimic.joint_name + "' which has no coordinate");
      // q_current = multiplier * q_target + offset
      off += mult * mimic.offset;
      mult *= mimic.multiplier;
      current = mimic.joint_name;
    }
    model.mimic_G_(i, independent_index_of.at(current)) = mult;
    model.mimic_offset_(i) = off;
  }

  // Limits of the independent joints.
  model.joint_lower_ = Eigen::VectorXd::Constant(nj, -kInf);
  model.joint_upper_ = Eigen::VectorXd::Constant(nj, kInf);
  model.joint_velocity_ = Eigen::VectorXd::Constant(nj, kInf);
  model.joint_effort_ = Eigen::VectorXd::Constant(nj, kInf);
  for (int j = 0; j < nj; ++j) {
    const urdf::JointConstSharedPtr joint = urdf->getJoint(model.joint_names_[static_cast<std::size_t>(j)]);
    if (!joint->limits) continue;
    const urdf::JointLimits& lim = *joint->limits;
    if (joint->type != urdf::Joint::CONTINUOUS) {
      if (lim.lower > lim.upper)
        throw std::runtime_error("ReferenceModel: joint '" + joint->name + "': lower limit > upper limit");
      model.joint_lower_(j) = lim.lower;
      model.joint_upper_(j) = lim.upper;
    }
    model.joint_velocity_(j) = lim.velocity;
    model.joint_effort_(j) = lim.effort;
  }

  // Merged bodies: a link whose parent joint is fixed belongs to its parent's body.
  for (std::size_t i = 0; i < model.links_.size(); ++i) {
    Link& link = model.links_[i];
    if (link.type == JointType::Fixed) {
      const Link& parent = model.links_[static_cast<std::size_t>(link.parent)];
      link.body = parent.body;
      link.in_body = compose(parent.in_body, link.origin);
    } else {
      link.body = static_cast<int>(model.body_names_.size());
      link.in_body = Pose();
      model.body_names_.push_back(link.name);
      model.body_root_link_.push_back(static_cast<int>(i));
    }
  }
  return model;
}

// ---------------------------------------------------------------------------------------------
// Sizes, names, limits
// ---------------------------------------------------------------------------------------------

int ReferenceModel::baseDofs() const { return floating_base_ ? 6 : 0; }
int ReferenceModel::nq() const { return (floating_base_ ? 7 : 0) + static_cast<int>(joint_names_.size()); }
int ReferenceModel::nv() const { return baseDofs() + static_cast<int>(joint_names_.size()); }
bool ReferenceModel::floatingBase() const { return floating_base_; }
const std::vector<std::string>& ReferenceModel::jointNames() const { return joint_names_; }
const std::vector<std::string>& ReferenceModel::frameNames() const { return frame_names_; }
const std::vector<std::string>& ReferenceModel::bodyNames() const { return body_names_; }
const std::vector<std::string>& ReferenceModel::fullJointNames() const { return full_joint_names_; }
const Eigen::MatrixXd& ReferenceModel::mimicMatrix() const { return mimic_G_; }
const Eigen::VectorXd& ReferenceModel::mimicOffset() const { return mimic_offset_; }
const Eigen::Vector3d& ReferenceModel::gravity() const { return gravity_; }
void ReferenceModel::setGravity(const Eigen::Vector3d& g) { gravity_ = g; }

int ReferenceModel::frameIndex(const std::string& name) const {
  for (std::size_t i = 0; i < frame_names_.size(); ++i)
    if (frame_names_[i] == name) return static_cast<int>(i);
  return -1;
}

int ReferenceModel::requireFrame(const std::string& name) const {
  const int index = frameIndex(name);
  if (index < 0) throw std::runtime_error("ReferenceModel: unknown frame '" + name + "'");
  return index;
}

std::vector<int> ReferenceModel::frameBody() const {
  std::vector<int> out;
  for (const Link& link : links_) out.push_back(link.body);
  return out;
}

Eigen::VectorXd ReferenceModel::lowerPositionLimit() const {
  Eigen::VectorXd out = Eigen::VectorXd::Constant(nq(), -kInf);
  out.tail(static_cast<Eigen::Index>(joint_names_.size())) = joint_lower_;
  return out;
}

Eigen::VectorXd ReferenceModel::upperPositionLimit() const {
  Eigen::VectorXd out = Eigen::VectorXd::Constant(nq(), kInf);
  out.tail(static_cast<Eigen::Index>(joint_names_.size())) = joint_upper_;
  return out;
}

Eigen::VectorXd ReferenceModel::velocityLimit() const {
  Eigen::VectorXd out = Eigen::VectorXd::Constant(nv(), kInf);
  out.tail(static_cast<Eigen::Index>(joint_names_.size())) = joint_velocity_;
  return out;
}

Eigen::VectorXd ReferenceModel::effortLimit() const {
  Eigen::VectorXd out = Eigen::VectorXd::Constant(nv(), kInf);
  out.tail(static_cast<Eigen::Index>(joint_names_.size())) = joint_effort_;
  return out;
}

void ReferenceModel::checkConfig(const Eigen::VectorXd& q) const {
  if (q.size() != nq())
    throw std::runtime_error("ReferenceModel: configuration has size " + std::to_string(q.size()) +
                             ", expected nq = " + std::to_string(nq()));
}

void ReferenceModel::checkTangent(const Eigen::VectorXd& v, const char* what) const {
  if (v.size() != nv())
    throw std::runtime_error(std::string("ReferenceModel: ") + what + " has size " +
                             std::to_string(v.size()) + ", expected nv = " + std::to_string(nv()));
}

Eigen::VectorXd ReferenceModel::fullJointPositions(const Eigen::VectorXd& q) const {
  checkConfig(q);
  const Eigen::VectorXd qj = q.tail(static_cast<Eigen::Index>(joint_names_.size()));
  return mimic_G_ * qj + mimic_offset_;
}

// ---------------------------------------------------------------------------------------------
// Configuration space
// ---------------------------------------------------------------------------------------------

Eigen::VectorXd ReferenceModel::neutral() const {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(nq());
  if (floating_base_) q(3) = 1.0;  // quaternion w
  return q;
}

Eigen::VectorXd ReferenceModel::integrate(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                          double dt) const {
  checkConfig(q);
  checkTangent(v, "velocity");
  Eigen::VectorXd out = q;
  const Eigen::Index nj = static_cast<Eigen::Index>(joint_names_.size());
  out.tail(nj) = q.tail(nj) + v.tail(nj) * dt;
  if (floating_base_) {
    const Eigen::Vector3d p = q.head<3>();
    const Eigen::Quaterniond quat = Eigen::Quaterniond(q(3), q(4), q(5), q(6)).normalized();
    const Eigen::Matrix3d R = quat.toRotationMatrix();
    const Eigen::Vector3d phi = v.head<3>() * dt;  // rotation vector, body frame
    const Eigen::Vector3d rho = v.segment<3>(3) * dt;
    const double theta = phi.norm();
    // SE(3) exponential: R_new = R Exp(phi), p_new = p + R V(phi) rho with
    // V = I + (1 - cos t)/t^2 [phi] + (t - sin t)/t^3 [phi]^2.
    double c1 = 0.0, c2 = 0.0;
    if (theta < 1e-3) {
      const double t2 = theta * theta;
      c1 = 0.5 - t2 / 24.0 + t2 * t2 / 720.0;
      c2 = 1.0 / 6.0 - t2 / 120.0 + t2 * t2 / 5040.0;
    } else {
      c1 = (1.0 - std::cos(theta)) / (theta * theta);
      c2 = (theta - std::sin(theta)) / (theta * theta * theta);
    }
    const Eigen::Matrix3d S = skew(phi);
    const Eigen::Matrix3d V = Eigen::Matrix3d::Identity() + c1 * S + c2 * S * S;
    Eigen::Quaterniond dquat = Eigen::Quaterniond::Identity();
    if (theta > 0.0) dquat = Eigen::Quaterniond(Eigen::AngleAxisd(theta, phi / theta));
    const Eigen::Quaterniond new_quat = (quat * dquat).normalized();
    out.head<3>() = p + R * V * rho;
    out(3) = new_quat.w();
    out(4) = new_quat.x();
    out(5) = new_quat.y();
    out(6) = new_quat.z();
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Kinematics
// ---------------------------------------------------------------------------------------------

ReferenceModel::Pose ReferenceModel::localPose(int index, const Eigen::VectorXd& q,
                                               const Eigen::VectorXd& q_full) const {
  const Link& link = links_[static_cast<std::size_t>(index)];
  Pose out;
  switch (link.type) {
    case JointType::Root:
      if (floating_base_) {
        out.p = q.head<3>();
        out.R = Eigen::Quaterniond(q(3), q(4), q(5), q(6)).normalized().toRotationMatrix();
      }
      break;
    case JointType::Fixed:
      out = link.origin;
      break;
    case JointType::Revolute: {
      const double angle = q_full(link.full_index);
      out.R = link.origin.R * Eigen::AngleAxisd(angle, link.axis).toRotationMatrix();
      out.p = link.origin.p;
      break;
    }
    case JointType::Prismatic: {
      const double d = q_full(link.full_index);
      out.R = link.origin.R;
      out.p = link.origin.p + link.origin.R * (link.axis * d);
      break;
    }
  }
  return out;
}

// Velocity of a link relative to its parent per unit joint rate, link coordinates.
ReferenceModel::Vector6d ReferenceModel::motionSubspace(int index) const {
  const Link& link = links_[static_cast<std::size_t>(index)];
  if (link.type == JointType::Revolute) return spatial(link.axis, Eigen::Vector3d::Zero());
  if (link.type == JointType::Prismatic) return spatial(Eigen::Vector3d::Zero(), link.axis);
  return Vector6d::Zero();
}

std::vector<ReferenceModel::Pose> ReferenceModel::worldPoses(const Eigen::VectorXd& q) const {
  const Eigen::VectorXd q_full = fullJointPositions(q);
  std::vector<Pose> world(links_.size());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const Pose local = localPose(static_cast<int>(i), q, q_full);
    const int parent = links_[i].parent;
    world[i] = parent < 0 ? local : compose(world[static_cast<std::size_t>(parent)], local);
  }
  return world;
}

ReferenceModel::Motion ReferenceModel::propagate(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                                 const Eigen::VectorXd& a,
                                                 const Eigen::Vector3d& gravity_used) const {
  checkConfig(q);
  checkTangent(v, "velocity");
  checkTangent(a, "acceleration");
  const Eigen::Index nj = static_cast<Eigen::Index>(joint_names_.size());
  const Eigen::VectorXd q_full = fullJointPositions(q);
  const Eigen::VectorXd qd_full = mimic_G_ * v.tail(nj);
  const Eigen::VectorXd qdd_full = mimic_G_ * a.tail(nj);

  Motion m;
  m.world.resize(links_.size());
  m.velocity.resize(links_.size());
  m.acceleration.resize(links_.size());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const Link& link = links_[i];
    const Pose local = localPose(static_cast<int>(i), q, q_full);
    if (link.parent < 0) {
      m.world[i] = local;
      // Fictitious upward acceleration -g accounts for gravity, expressed in the root frame.
      const Vector6d minus_g = spatial(Eigen::Vector3d::Zero(), -(local.R.transpose() * gravity_used));
      if (floating_base_) {
        m.velocity[i] = v.head<6>();
        m.acceleration[i] = a.head<6>() + minus_g;
      } else {
        m.velocity[i] = Vector6d::Zero();
        m.acceleration[i] = minus_g;
      }
      continue;
    }
    const std::size_t p = static_cast<std::size_t>(link.parent);
    m.world[i] = compose(m.world[p], local);
    const Vector6d S = motionSubspace(static_cast<int>(i));
    const double qd = link.full_index >= 0 ? qd_full(link.full_index) : 0.0;
    const double qdd = link.full_index >= 0 ? qdd_full(link.full_index) : 0.0;
    const Vector6d vJ = S * qd;
    m.velocity[i] = motionToChild(local, m.velocity[p]) + vJ;
    m.acceleration[i] = motionToChild(local, m.acceleration[p]) + S * qdd + crossMotion(m.velocity[i], vJ);
  }
  return m;
}

ReferenceModel::Pose ReferenceModel::framePose(const Eigen::VectorXd& q, const std::string& frame) const {
  checkConfig(q);
  const int index = requireFrame(frame);
  return worldPoses(q)[static_cast<std::size_t>(index)];
}

Eigen::MatrixXd ReferenceModel::frameJacobian(const Eigen::VectorXd& q, const std::string& frame,
                                              const Eigen::Vector3d& point_in_frame,
                                              bool world_aligned) const {
  checkConfig(q);
  const std::size_t index = static_cast<std::size_t>(requireFrame(frame));
  // Column k = velocity of the point when v = e_k.
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, nv());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(nv());
  for (int k = 0; k < nv(); ++k) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(nv(), k);
    const Motion m = propagate(q, e, zero, Eigen::Vector3d::Zero());
    const Eigen::Vector3d w = angular(m.velocity[index]);
    const Eigen::Vector3d v_point = linear(m.velocity[index]) + w.cross(point_in_frame);
    const Eigen::Matrix3d R = world_aligned ? m.world[index].R : Eigen::Matrix3d::Identity();
    J.block<3, 1>(0, k) = R * w;
    J.block<3, 1>(3, k) = R * v_point;
  }
  return J;
}

ReferenceModel::Vector6d ReferenceModel::frameBiasAcceleration(const Eigen::VectorXd& q,
                                                               const Eigen::VectorXd& v,
                                                               const std::string& frame,
                                                               const Eigen::Vector3d& point_in_frame,
                                                               bool world_aligned) const {
  const std::size_t index = static_cast<std::size_t>(requireFrame(frame));
  const Motion m = propagate(q, v, Eigen::VectorXd::Zero(nv()), Eigen::Vector3d::Zero());
  // Body twist (w; v_o) and its time derivative (dw; dv_o), both in link coordinates.
  const Eigen::Vector3d w = angular(m.velocity[index]);
  const Eigen::Vector3d dw = angular(m.acceleration[index]);
  const Eigen::Vector3d u = linear(m.velocity[index]) + w.cross(point_in_frame);        // point vel.
  const Eigen::Vector3d du = linear(m.acceleration[index]) + dw.cross(point_in_frame);  // d/dt u
  if (!world_aligned) return spatial(dw, du);
  // World aligned: J v = (R w; R u), d/dt = (R dw + R (w x w); R (du + w x u)).
  const Eigen::Matrix3d& R = m.world[index].R;
  return spatial(R * dw, R * (du + w.cross(u)));
}

// ---------------------------------------------------------------------------------------------
// Mass properties
// ---------------------------------------------------------------------------------------------

double ReferenceModel::totalMass() const {
  double total = 0.0;
  for (const Link& link : links_) total += link.mass;
  return total;
}

Eigen::Vector3d ReferenceModel::centerOfMass(const Eigen::VectorXd& q) const {
  checkConfig(q);
  const std::vector<Pose> world = worldPoses(q);
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < links_.size(); ++i)
    weighted += links_[i].mass * (world[i].p + world[i].R * links_[i].com);
  const double total = totalMass();
  return total > 0.0 ? Eigen::Vector3d(weighted / total) : Eigen::Vector3d::Zero();
}

Eigen::MatrixXd ReferenceModel::comJacobian(const Eigen::VectorXd& q) const {
  checkConfig(q);
  Eigen::MatrixXd Jc = Eigen::MatrixXd::Zero(3, nv());
  const double total = totalMass();
  if (total <= 0.0) return Jc;
  for (const Link& link : links_) {
    if (link.mass == 0.0) continue;
    const Eigen::MatrixXd J = frameJacobian(q, link.name, link.com, true);
    Jc += link.mass / total * J.bottomRows(3);
  }
  return Jc;
}

Eigen::VectorXd ReferenceModel::inertialParameters() const {
  const std::size_t nbodies = body_names_.size();
  std::vector<double> mass(nbodies, 0.0);
  std::vector<Eigen::Vector3d> first_moment(nbodies, Eigen::Vector3d::Zero());
  std::vector<Eigen::Matrix3d> inertia_origin(nbodies, Eigen::Matrix3d::Zero());
  for (const Link& link : links_) {
    const std::size_t b = static_cast<std::size_t>(link.body);
    // CoM and rotational inertia about the CoM, in the body frame.
    const Eigen::Vector3d c = link.in_body.p + link.in_body.R * link.com;
    const Eigen::Matrix3d Ic = link.in_body.R * link.inertia_com * link.in_body.R.transpose();
    mass[b] += link.mass;
    first_moment[b] += link.mass * c;
    // Parallel axis theorem: about the body origin, I = Ic + m (|c|^2 1 - c c^T).
    inertia_origin[b] += Ic + link.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  }
  Eigen::VectorXd phi(10 * static_cast<Eigen::Index>(nbodies));
  for (std::size_t b = 0; b < nbodies; ++b) {
    const Eigen::Matrix3d& I = inertia_origin[b];
    phi.segment<10>(10 * static_cast<Eigen::Index>(b)) << mass[b], first_moment[b].x(), first_moment[b].y(),
        first_moment[b].z(), I(0, 0), I(0, 1), I(1, 1), I(0, 2), I(1, 2), I(2, 2);
  }
  return phi;
}

// ---------------------------------------------------------------------------------------------
// Dynamics
// ---------------------------------------------------------------------------------------------

Eigen::VectorXd ReferenceModel::rneaWithGravity(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                                const Eigen::VectorXd& a, const Eigen::Vector3d& g) const {
  const Motion m = propagate(q, v, a, g);
  const Eigen::VectorXd q_full = fullJointPositions(q);

  // Forward: net spatial force each link needs, link coordinates.
  std::vector<Vector6d> force(links_.size());
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const Link& link = links_[i];
    const Vector6d Iv = inertiaTimes(link.mass, link.com, link.inertia_com, m.velocity[i]);
    force[i] = inertiaTimes(link.mass, link.com, link.inertia_com, m.acceleration[i]) +
               crossForce(m.velocity[i], Iv);
  }

  // Backward: accumulate into parents, project on the joint axes.
  Eigen::VectorXd tau_full = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(full_joint_names_.size()));
  for (std::size_t k = links_.size(); k-- > 0;) {
    const Link& link = links_[k];
    if (link.full_index >= 0) tau_full(link.full_index) = motionSubspace(static_cast<int>(k)).dot(force[k]);
    if (link.parent >= 0) {
      const Pose local = localPose(static_cast<int>(k), q, q_full);
      force[static_cast<std::size_t>(link.parent)] += forceToParent(local, force[k]);
    }
  }

  Eigen::VectorXd tau(nv());
  if (floating_base_) tau.head<6>() = force[0];  // spatial force on the root, root frame
  tau.tail(static_cast<Eigen::Index>(joint_names_.size())) = mimic_G_.transpose() * tau_full;
  return tau;
}

Eigen::VectorXd ReferenceModel::rnea(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                     const Eigen::VectorXd& a) const {
  return rneaWithGravity(q, v, a, gravity_);
}

Eigen::VectorXd ReferenceModel::nonLinearEffects(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  return rneaWithGravity(q, v, Eigen::VectorXd::Zero(nv()), gravity_);
}

Eigen::MatrixXd ReferenceModel::massMatrix(const Eigen::VectorXd& q) const {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(nv());
  const Eigen::Vector3d no_gravity = Eigen::Vector3d::Zero();
  const Eigen::VectorXd bias = rneaWithGravity(q, zero, zero, no_gravity);
  Eigen::MatrixXd M(nv(), nv());
  for (int i = 0; i < nv(); ++i)
    M.col(i) = rneaWithGravity(q, zero, Eigen::VectorXd::Unit(nv(), i), no_gravity) - bias;
  return M;
}

}  // namespace mrqp::test
