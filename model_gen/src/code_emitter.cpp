#include "code_emitter.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "linear_expr.hpp"
#include "probe_emitter.hpp"
#include "runtime_text.hpp"

namespace mrqp::gen {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

std::string str(int i) { return std::to_string(i); }

/// Element i of a runtime vector: "x[i]" for the raw pointers vb/ab/f, "x(i)" for Eigen objects.
std::string element(const std::string& x, int i) {
  const bool pointer = x == "vb" || x == "ab" || x == "f" || x == "Fp" || x == "h" || x == "I";
  return pointer ? x + "[" + std::to_string(i) + "]" : x + "(" + std::to_string(i) + ")";
}

std::string cstring(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string limitLiteral(double x) {
  if (std::isinf(x)) return x > 0 ? "kInf" : "-kInf";
  return literal(x);
}

/// Components of v scaled and added as symbols "prefix(k)" (k = offset + component).
std::string dotConst(const Vector3d& a, const std::string& vec, int offset) {
  LinearExpr e;
  for (int c = 0; c < 3; ++c) e.add(a(c), element(vec, offset + c));
  return e.str();
}

/// Emits `dst(offset + c) op= scale * a(c)` for the non-zero constant components a(c).
void addScaledConst(std::ostream& o, const std::string& ind, const std::string& dst, int offset,
                    const Vector3d& a, const std::string& scale) {
  for (int c = 0; c < 3; ++c) {
    const double k = snap(a(c));
    if (k == 0.0) continue;
    LinearExpr e;
    e.add(k, scale);
    o << ind << element(dst, offset + c) << " += " << e.str() << ";\n";
  }
}

/// Components of (w × a) where w is the runtime 3-vector "w(off+i)" and a a constant.
std::array<std::string, 3> crossRuntimeConst(const std::string& w, int off, const Vector3d& a) {
  auto W = [&](int i) { return element(w, off + i); };
  std::array<std::string, 3> out;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    LinearExpr e;
    e.add(a(k), W(j)).add(-a(j), W(k));
    out[idx(i)] = e.str();
  }
  return out;
}

/// Spatial inertia (m, h, I) times the motion "m(0..5)": (I ω + h × v, m v − h × ω).
std::array<std::string, 6> inertiaTimes(const BodyInertia& in, const std::string& m) {
  auto M = [&](int i) { return element(m, i); };
  std::array<std::string, 6> out;
  const Vector3d& h = in.h;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    LinearExpr n;
    for (int c = 0; c < 3; ++c) n.add(in.I(i, c), M(c));
    n.add(h(j), M(3 + k)).add(-h(k), M(3 + j));  // (h × v)_i
    out[idx(i)] = n.str();
    LinearExpr f;
    f.add(in.mass, M(3 + i));
    f.add(-h(j), M(k)).add(h(k), M(j));  // −(h × ω)_i
    out[idx(3 + i)] = f.str();
  }
  return out;
}

bool isZeroInertia(const BodyInertia& in) { return in.mass == 0.0 && in.h.isZero(0.0) && in.I.isZero(0.0); }

class Emitter {
 public:
  Emitter(const KinematicTree& t, std::string name, std::string origin)
      : t_(t), name_(std::move(name)), origin_(std::move(origin)), nb_(static_cast<int>(t.bodies.size())) {}

  std::string header() const;
  std::string source() const;

 private:
  const TreeJoint& joint(int b) const { return t_.bodies[idx(b)].joint; }
  bool moving(int b) const {
    const auto k = joint(b).kind;
    return k == JointKind::Revolute || k == JointKind::Prismatic;
  }
  bool floatingRoot() const { return t_.floating_base; }
  /// Joint position / velocity / acceleration expressions of a (possibly mimic) joint.
  std::string jointPos(int b) const {
    const auto& j = joint(b);
    LinearExpr e;
    e.add(j.multiplier, "q[" + str(j.q_index) + "]").add(j.offset, "");
    return e.str();
  }
  std::string scaled(int b, const std::string& x) const {
    LinearExpr e;
    e.add(joint(b).multiplier, x);
    return e.str();
  }

  /// The regressor is fixed-size when it fits Eigen's stack limit (128 KiB), else nv × dynamic,
  /// sized once by the caller (regressor() never resizes it).
  std::string regressorType() const {
    const long entries = static_cast<long>(t_.nv) * 10 * nb_;
    if (entries * 8 <= 131072) return "using Regressor = Eigen::Matrix<double, nv, nparams>;\n";
    return "/// Too large for a fixed-size matrix: construct once as Regressor(nv, nparams).\n"
           "using Regressor = Eigen::Matrix<double, nv, Eigen::Dynamic>;\n";
  }
  void emitLocalTransforms(std::ostream& o) const;
  void emitForwardPass(std::ostream& o) const;
  void emitBackwardTorques(std::ostream& o) const;
  void emitCrba(std::ostream& o) const;
  void emitChainTables(std::ostream& o) const;
  void emitTables(std::ostream& o) const;
  void emitIntegrate(std::ostream& o) const;

  const KinematicTree& t_;
  std::string name_;
  std::string origin_;
  int nb_;
};

std::string Emitter::header() const {
  std::ostringstream o;
  const int nj = static_cast<int>(t_.joint_names.size());
  o << "// Generated by mrqp-gen from " << origin_ << ". Do not edit: regenerate.\n"
    << "// Model '" << t_.robot_name << "': " << nb_ << " bodies, " << t_.frames.size() << " frames, nq "
    << t_.nq << ", nv " << t_.nv << (floatingRoot() ? ", floating base" : ", fixed base") << ".\n"
    << "// Conventions: docs/model_gen.md (spatial vectors angular first; floating-base twist in the root "
       "frame).\n"
    << "#pragma once\n\n#include <Eigen/Core>\n#include <array>\n\n"
    << "namespace " << name_ << " {\n\n"
    << "inline constexpr int nq = " << t_.nq << ";\n"
    << "inline constexpr int nv = " << t_.nv << ";\n"
    << "inline constexpr int njoints = " << nj << ";\n"
    << "inline constexpr int nbodies = " << nb_ << ";\n"
    << "inline constexpr int nframes = " << t_.frames.size() << ";\n"
    << "inline constexpr int nparams = 10 * nbodies;\n"
    << "inline constexpr int ncollision = " << t_.shapes.size() << ";\n"
    << "inline constexpr bool floating_base = " << (floatingRoot() ? "true" : "false") << ";\n\n"
    << "using ConfigVector = Eigen::Matrix<double, nq, 1>;\n"
    << "using TangentVector = Eigen::Matrix<double, nv, 1>;\n"
    << "using MassMatrix = Eigen::Matrix<double, nv, nv>;\n"
    << "using Jacobian = Eigen::Matrix<double, 6, nv>;\n"
    << "using ComJacobian = Eigen::Matrix<double, 3, nv>;\n"
    << "using ParamVector = Eigen::Matrix<double, nparams, 1>;\n"
    << regressorType() << "using Motion = Eigen::Matrix<double, 6, 1>;\n\n"
    << "/// A placement: x_parent = R x + p.\n"
    << "struct Pose {\n  Eigen::Matrix3d R;\n  Eigen::Vector3d p;\n};\n\n"
    << "enum class ReferenceFrame { Local, WorldAligned };\n"
    << "enum class ShapeType { Box, Cylinder, Sphere, ConvexMesh };\n\n"
    << "/// Collision geometry in its body's frame. Box: size = full extents; cylinder: (radius,\n"
    << "/// length) along z; sphere: (radius); convex mesh: hull vertices (x, y, z) in the shape frame.\n"
    << "struct CollisionShape {\n  int body;\n  ShapeType type;\n  double size[3];\n  double R[9];  // "
       "row-major\n"
    << "  double p[3];\n  const double* vertices;\n  int nvertices;\n  const char* link;\n};\n\n"
    << "extern const std::array<const char*, njoints> joint_names;\n"
    << "extern const std::array<const char*, nbodies> body_names;\n"
    << "extern const std::array<int, nbodies> body_parent;\n"
    << "extern const std::array<const char*, nframes> frame_names;\n"
    << "extern const std::array<int, nframes> frame_body;\n"
    << "extern const std::array<double, nq> q_lower;\n"
    << "extern const std::array<double, nq> q_upper;\n"
    << "extern const std::array<double, nv> v_limit;\n"
    << "extern const std::array<double, nv> effort_limit;\n"
    << "extern const std::array<CollisionShape, ncollision> collision_shapes;\n\n"
    << "/// Work space of the algorithms; fixed size, no allocation.\n"
    << "struct Data {\n"
    << "  std::array<Eigen::Matrix3d, nbodies> R;   ///< world orientation of each body (after "
       "forwardKinematics)\n"
    << "  std::array<Eigen::Vector3d, nbodies> p;   ///< world position of each body origin\n"
    << "  std::array<Eigen::Matrix3d, nbodies> Rl;  ///< orientation in the parent body\n"
    << "  std::array<Eigen::Vector3d, nbodies> pl;  ///< origin in the parent body\n"
    << "  std::array<Motion, nbodies> v;            ///< body twist, body coordinates\n"
    << "  std::array<Motion, nbodies> abias;        ///< J̇v of each body (zero joint acceleration, no "
       "gravity)\n"
    << "  std::array<Motion, nbodies> a;            ///< spatial acceleration incl. gravity (rnea)\n"
    << "  std::array<Motion, nbodies> f;            ///< body wrenches (rnea)\n"
    << "  std::array<double, nbodies> cm;           ///< composite mass (crba)\n"
    << "  std::array<Eigen::Vector3d, nbodies> ch;  ///< composite first moment (crba, com)\n"
    << "  std::array<Eigen::Matrix3d, nbodies> cI;  ///< composite rotational inertia (crba)\n"
    << "  Eigen::Vector3d gravity{0.0, 0.0, -9.81};\n"
    << "};\n\n"
    << "int frameIndex(const char* name) noexcept;\n"
    << "double totalMass() noexcept;\n"
    << "void neutral(ConfigVector& q) noexcept;\n"
    << "void integrate(const ConfigVector& q, const TangentVector& v, double dt, ConfigVector& out) "
       "noexcept;\n"
    << "void forwardKinematics(Data& d, const ConfigVector& q) noexcept;\n"
    << "void forwardKinematics(Data& d, const ConfigVector& q, const TangentVector& v) noexcept;\n"
    << "Pose framePose(const Data& d, int frame) noexcept;\n"
    << "void frameJacobian(const Data& d, int frame, const Eigen::Vector3d& point, ReferenceFrame rf,\n"
    << "                   Jacobian& J) noexcept;\n"
    << "Motion frameBiasAcceleration(const Data& d, int frame, const Eigen::Vector3d& point,\n"
    << "                             ReferenceFrame rf) noexcept;\n"
    << "Eigen::Vector3d centerOfMass(const Data& d) noexcept;\n"
    << "void comJacobian(Data& d, ComJacobian& Jc) noexcept;\n"
    << "void crba(Data& d, const ConfigVector& q, MassMatrix& M) noexcept;\n"
    << "void nonLinearEffects(Data& d, const ConfigVector& q, const TangentVector& v, TangentVector& N) "
       "noexcept;\n"
    << "void rnea(Data& d, const ConfigVector& q, const TangentVector& v, const TangentVector& a,\n"
    << "          TangentVector& tau) noexcept;\n"
    << "void regressor(Data& d, const ConfigVector& q, const TangentVector& v, const TangentVector& a,\n"
    << "               Regressor& Y) noexcept;\n"
    << "void inertialParameters(ParamVector& phi) noexcept;\n\n"
    << "}  // namespace " << name_ << "\n";
  return o.str();
}

void Emitter::emitTables(std::ostream& o) const {
  auto list = [&](const char* type, const char* n, int count, auto item) {
    o << "const std::array<" << type << ", " << count << "> " << n << " = {";
    for (int i = 0; i < count; ++i) o << (i ? ", " : "") << item(i);
    o << "};\n";
  };
  list("const char*", "joint_names", static_cast<int>(t_.joint_names.size()),
       [&](int i) { return cstring(t_.joint_names[idx(i)]); });
  list("const char*", "body_names", nb_, [&](int i) { return cstring(t_.bodies[idx(i)].name); });
  list("int", "body_parent", nb_, [&](int i) { return str(t_.bodies[idx(i)].parent); });
  const int nf = static_cast<int>(t_.frames.size());
  list("const char*", "frame_names", nf, [&](int i) { return cstring(t_.frames[idx(i)].name); });
  list("int", "frame_body", nf, [&](int i) { return str(t_.frames[idx(i)].body); });
  list("double", "q_lower", t_.nq, [&](int i) { return limitLiteral(t_.q_lower[idx(i)]); });
  list("double", "q_upper", t_.nq, [&](int i) { return limitLiteral(t_.q_upper[idx(i)]); });
  list("double", "v_limit", t_.nv, [&](int i) { return limitLiteral(t_.v_limit[idx(i)]); });
  list("double", "effort_limit", t_.nv, [&](int i) { return limitLiteral(t_.effort_limit[idx(i)]); });

  o << "\nnamespace {\n";
  o << "constexpr double frame_R[" << nf << "][9] = {";
  for (int i = 0; i < nf; ++i) {
    o << (i ? ",\n    " : "\n    ") << "{";
    for (int k = 0; k < 9; ++k) o << (k ? ", " : "") << literal(snap(t_.frames[idx(i)].R(k / 3, k % 3)));
    o << "}";
  }
  o << "};\n";
  o << "constexpr double frame_p[" << nf << "][3] = {";
  for (int i = 0; i < nf; ++i) {
    o << (i ? ",\n    " : "\n    ") << "{";
    for (int k = 0; k < 3; ++k) o << (k ? ", " : "") << literal(snap(t_.frames[idx(i)].p(k)));
    o << "}";
  }
  o << "};\n";
  for (size_t s = 0; s < t_.shapes.size(); ++s) {
    const auto& sh = t_.shapes[s];
    if (sh.kind != ShapeKind::ConvexMesh) continue;
    o << "constexpr double shape" << s << "_vertices[" << 3 * sh.vertices.size() << "] = {";
    for (size_t v = 0; v < sh.vertices.size(); ++v)
      for (int k = 0; k < 3; ++k) o << (v || k ? ", " : "") << literal(sh.vertices[v](k));
    o << "};\n";
  }
  o << "}  // namespace\n\n";
  o << "const std::array<CollisionShape, ncollision> collision_shapes = {{";
  for (size_t s = 0; s < t_.shapes.size(); ++s) {
    const auto& sh = t_.shapes[s];
    static const char* kinds[] = {"ShapeType::Box", "ShapeType::Cylinder", "ShapeType::Sphere",
                                  "ShapeType::ConvexMesh"};
    o << (s ? ",\n    " : "\n    ") << "{" << sh.body << ", " << kinds[static_cast<int>(sh.kind)] << ", {"
      << literal(sh.size(0)) << ", " << literal(sh.size(1)) << ", " << literal(sh.size(2)) << "}, {";
    for (int k = 0; k < 9; ++k) o << (k ? ", " : "") << literal(snap(sh.R(k / 3, k % 3)));
    o << "}, {" << literal(sh.p(0)) << ", " << literal(sh.p(1)) << ", " << literal(sh.p(2)) << "}, ";
    if (sh.kind == ShapeKind::ConvexMesh)
      o << "shape" << s << "_vertices, " << sh.vertices.size();
    else
      o << "nullptr, 0";
    o << ", " << cstring(sh.link) << "}";
  }
  o << "}};\n\n";
}

void Emitter::emitLocalTransforms(std::ostream& o) const {
  o << "/// Rl, pl of every body from q (Rl column-major: Rl(i, j) = R[i + 3 j]).\n"
       "inline void localTransforms(Data& d, const ConfigVector& qv) noexcept {\n"
       "  const double* q = qv.data();\n  (void)q;\n";
  if (floatingRoot()) {
    o << "  {\n"
         "    const double n = std::sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]);\n"
         "    const double w = q[3] / n, x = q[4] / n, y = q[5] / n, z = q[6] / n;\n"
         "    double* R = d.Rl[0].data();\n"
         "    R[0] = 1 - 2 * (y * y + z * z); R[3] = 2 * (x * y - w * z); R[6] = 2 * (x * z + w * y);\n"
         "    R[1] = 2 * (x * y + w * z); R[4] = 1 - 2 * (x * x + z * z); R[7] = 2 * (y * z - w * x);\n"
         "    R[2] = 2 * (x * z - w * y); R[5] = 2 * (y * z + w * x); R[8] = 1 - 2 * (x * x + y * y);\n"
         "    d.pl[0] = qv.head<3>();\n"
         "  }\n";
  } else {
    o << "  d.Rl[0].setIdentity();\n  d.pl[0].setZero();\n";
  }
  for (int b = 1; b < nb_; ++b) {
    const TreeBody& body = t_.bodies[idx(b)];
    const TreeJoint& j = body.joint;
    const Vector3d a = j.axis;
    o << "  {  // body " << b << " '" << body.name << "', joint '" << j.name << "'"
      << (j.mimic ? " (mimics '" + j.mimicked + "')" : std::string()) << "\n"
      << "    double* R = d.Rl[" << b << "].data();\n    double* t = d.pl[" << b << "].data();\n";
    Matrix3d A = Matrix3d::Zero(), B = Matrix3d::Zero(), C = Matrix3d::Zero();
    Vector3d t0 = body.p0, dir = Vector3d::Zero();
    std::string var = "x";
    if (j.kind == JointKind::Revolute) {
      o << "    const double th = " << jointPos(b) << ";\n"
        << "    const double c = std::cos(th), s = std::sin(th);\n";
      // Rl = R0 · (a aᵀ + c (I − a aᵀ) + s [a]×)
      Matrix3d ax;
      ax << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
      A = body.R0 * (a * a.transpose());
      B = body.R0 * (Matrix3d::Identity() - a * a.transpose());
      C = body.R0 * ax;
    } else {
      o << "    const double x = " << jointPos(b) << ";\n";
      A = body.R0;
      dir = body.R0 * a;  // pl = p0 + R0 a x
    }
    for (int col = 0; col < 3; ++col)
      for (int row = 0; row < 3; ++row) {
        LinearExpr e;
        e.add(A(row, col), "").add(B(row, col), "c").add(C(row, col), "s");
        o << "    R[" << row + 3 * col << "] = " << e.str() << ";\n";
      }
    for (int k = 0; k < 3; ++k) {
      LinearExpr e;
      e.add(t0(k), "").add(dir(k), var);
      o << "    t[" << k << "] = " << e.str() << ";\n";
    }
    o << "  }\n";
  }
  o << "}\n\n";
  o << "inline void worldPoses(Data& d) noexcept {\n  d.R[0] = d.Rl[0];\n  d.p[0] = d.pl[0];\n";
  for (int b = 1; b < nb_; ++b) {
    const int p = t_.bodies[idx(b)].parent;
    o << "  composePose(d.R[" << p << "].data(), d.p[" << p << "].data(), d.Rl[" << b << "].data(), d.pl["
      << b << "].data(), d.R[" << b << "].data(), d.p[" << b << "].data());\n";
  }
  o << "}\n\n";
}

// Forward pass (body coordinates):
//   v_i = X v_λ + S q̇,  acc_i = X acc_λ + S q̈ + v_i × S q̇, and with `forces` f_i = I acc_i + v_i ×* I v_i.
// `acc` adds S q̈; `gravity` starts from the fictitious base acceleration −g. Scalar code on
// raw pointers, specialised to each joint's axis and each body's inertia constants.
void Emitter::emitForwardPass(std::ostream& o) const {
  o << "inline void forwardPass(Data& d, const TangentVector& vv, const TangentVector* acc, bool gravity,\n"
       "                        bool forces, std::array<Motion, nbodies>& A) noexcept {\n"
       "  const double* v = vv.data();\n  const double* aa = acc ? acc->data() : nullptr;\n  (void)v;\n";
  if (nb_ == 1) o << "  (void)aa;  // no joint: the root alone\n";
  if (floatingRoot()) {
    o << "  d.v[0] = vv.head<6>();\n"
         "  if (acc) A[0] = acc->head<6>(); else A[0].setZero();\n"
         "  if (gravity) {\n    double g[3];\n    rotateT(d.Rl[0].data(), d.gravity.data(), g);\n"
         "    for (int k = 0; k < 3; ++k) A[0](3 + k) -= g[k];\n  }\n";
  } else {
    o << "  d.v[0].setZero();\n  A[0].setZero();\n"
         "  if (gravity) A[0].tail<3>() = -d.gravity;\n";
  }
  for (int b = 1; b < nb_; ++b) {
    const TreeBody& body = t_.bodies[idx(b)];
    const TreeJoint& j = body.joint;
    const int p = body.parent;
    const bool parentAtRest = p == 0 && !floatingRoot();
    const std::string X = "d.Rl[" + str(b) + "].data(), d.pl[" + str(b) + "].data()";
    o << "  {  // body " << b << " '" << body.name << "'\n"
      << "    double* vb = d.v[" << b << "].data();\n    double* ab = A[" << b << "].data();\n"
      << "    const double qd = " << scaled(b, "v[" + str(j.v_index) + "]") << ";\n";
    if (parentAtRest)
      o << "    for (int k = 0; k < 6; ++k) vb[k] = 0.0;\n";
    else
      o << "    motionToChild(" << X << ", d.v[" << p << "].data(), vb);\n";
    const int off = j.kind == JointKind::Revolute ? 0 : 3;
    addScaledConst(o, "    ", "vb", off, j.axis, "qd");
    o << "    motionToChild(" << X << ", A[" << p << "].data(), ab);\n";
    o << "    if (aa) {\n      const double qdd = " << scaled(b, "aa[" + str(j.v_index) + "]") << ";\n";
    addScaledConst(o, "      ", "ab", off, j.axis, "qdd");
    o << "    }\n";
    if (!parentAtRest) {
      // v × (S q̇): revolute S=(a,0): (ω × a, vl × a)·q̇ ; prismatic S=(0,a): (0, ω × a)·q̇
      const auto wa = crossRuntimeConst("vb", 0, j.axis);
      const auto va = crossRuntimeConst("vb", 3, j.axis);
      for (int c = 0; c < 3; ++c) {
        if (j.kind == JointKind::Revolute) {
          if (wa[idx(c)] != "0.0") o << "    ab[" << c << "] += qd * (" << wa[idx(c)] << ");\n";
          if (va[idx(c)] != "0.0") o << "    ab[" << 3 + c << "] += qd * (" << va[idx(c)] << ");\n";
        } else if (wa[idx(c)] != "0.0") {
          o << "    ab[" << 3 + c << "] += qd * (" << wa[idx(c)] << ");\n";
        }
      }
    }
    o << "  }\n";
  }
  o << "  if (!forces) return;\n";
  for (int b = 0; b < nb_; ++b) {
    const BodyInertia& in = t_.bodies[idx(b)].inertia;
    if (isZeroInertia(in) || (b == 0 && !floatingRoot())) {
      o << "  d.f[" << b << "].setZero();\n";
      continue;
    }
    const auto Iv = inertiaTimes(in, "vb");
    const auto Ia = inertiaTimes(in, "ab");
    o << "  {  // f = I a + v ×* I v\n    const double* vb = d.v[" << b
      << "].data();\n    const double* ab = A[" << b << "].data();\n    double* f = d.f[" << b
      << "].data();\n"
      << "    const double n0 = " << Iv[0] << ", n1 = " << Iv[1] << ", n2 = " << Iv[2] << ";\n"
      << "    const double l0 = " << Iv[3] << ", l1 = " << Iv[4] << ", l2 = " << Iv[5] << ";\n"
      << "    f[0] = " << Ia[0] << " + vb[1] * n2 - vb[2] * n1 + vb[4] * l2 - vb[5] * l1;\n"
      << "    f[1] = " << Ia[1] << " + vb[2] * n0 - vb[0] * n2 + vb[5] * l0 - vb[3] * l2;\n"
      << "    f[2] = " << Ia[2] << " + vb[0] * n1 - vb[1] * n0 + vb[3] * l1 - vb[4] * l0;\n"
      << "    f[3] = " << Ia[3] << " + vb[1] * l2 - vb[2] * l1;\n"
      << "    f[4] = " << Ia[4] << " + vb[2] * l0 - vb[0] * l2;\n"
      << "    f[5] = " << Ia[5] << " + vb[0] * l1 - vb[1] * l0;\n  }\n";
  }
  o << "}\n\n";
}

// Backward pass: τ_i = Sᵀ f_i (scaled for mimics), f_λ += X* f_i.
void Emitter::emitBackwardTorques(std::ostream& o) const {
  o << "inline void backwardTorques(Data& d, TangentVector& tv) noexcept {\n  tv.setZero();\n"
       "  double* tau = tv.data();\n";
  if (nb_ == 1) o << "  (void)tau;  // no joint: the root alone\n";
  for (int b = nb_ - 1; b >= 1; --b) {
    const TreeBody& body = t_.bodies[idx(b)];
    const TreeJoint& j = body.joint;
    const int off = j.kind == JointKind::Revolute ? 0 : 3;
    o << "  {\n    const double* f = d.f[" << b << "].data();\n    tau[" << j.v_index
      << "] += " << scaled(b, "(" + dotConst(j.axis, "f", off) + ")") << ";\n  }\n";
    if (body.parent == 0 && !floatingRoot()) continue;
    o << "  forceToParent(d.Rl[" << b << "].data(), d.pl[" << b << "].data(), d.f[" << b << "].data(), d.f["
      << body.parent << "].data());\n";
  }
  if (floatingRoot()) o << "  tv.head<6>() = d.f[0];\n";
  o << "}\n\n";
}

// Composite-rigid-body algorithm. Each body's composite inertia and its column F = Ic S are
// written out; the walk up its ancestors (F moved body by body, M entries S_cᵀ F) is the
// table-driven chainToRoot, which keeps the generated code linear in the number of bodies.
void Emitter::emitCrba(std::ostream& o) const {
  o << "void crba(Data& d, const ConfigVector& q, MassMatrix& M) noexcept {\n"
       "  localTransforms(d, q);\n  M.setZero();\n"
       "  for (int b = 0; b < nbodies; ++b) {\n"
       "    d.cm[ix(b)] = bodyMass[b];\n"
       "    d.ch[ix(b)] = Eigen::Map<const Eigen::Vector3d>(bodyFirstMoment[b]);\n"
       "    d.cI[ix(b)] = Eigen::Map<const Eigen::Matrix3d>(bodyRotationalInertia[b]);\n  }\n"
       "  double Fp[6];\n";
  if (nb_ == 1) o << "  (void)Fp;  // no joint: the root alone\n";
  for (int b = nb_ - 1; b >= 1; --b) {
    const TreeBody& body = t_.bodies[idx(b)];
    const TreeJoint& j = body.joint;
    const int vi = j.v_index;
    o << "  {  // body " << b << " '" << body.name << "'\n"
      << "    const double* I = d.cI[" << b << "].data();\n    const double* h = d.ch[" << b
      << "].data();\n    (void)I;\n    (void)h;\n";
    const auto ha = crossRuntimeConst("h", 0, j.axis);  // h × a
    if (j.kind == JointKind::Revolute) {
      // F = (Ī a, a × h)
      for (int k = 0; k < 3; ++k) {
        LinearExpr e;
        for (int c = 0; c < 3; ++c) e.add(j.axis(c), element("I", k + 3 * c));
        o << "    Fp[" << k << "] = " << e.str() << ";\n";
      }
      for (int k = 0; k < 3; ++k) o << "    Fp[" << 3 + k << "] = -(" << ha[idx(k)] << ");\n";
    } else {
      // F = (h × a, m a)
      for (int k = 0; k < 3; ++k) o << "    Fp[" << k << "] = " << ha[idx(k)] << ";\n";
      for (int k = 0; k < 3; ++k) {
        LinearExpr e;
        e.add(j.axis(k), "d.cm[" + str(b) + "]");
        o << "    Fp[" << 3 + k << "] = " << e.str() << ";\n";
      }
    }
    const int off = j.kind == JointKind::Revolute ? 0 : 3;
    LinearExpr diag;
    diag.add(j.multiplier * j.multiplier, "(" + dotConst(j.axis, "Fp", off) + ")");
    o << "    M(" << vi << ", " << vi << ") += " << diag.str() << ";\n";
    if (body.parent > 0 || floatingRoot()) {
      o << "    chainToRoot(d, " << b << ", Fp, M);\n";
      o << "    addCompositeToParent(d, " << b << ", " << body.parent << ");\n";
    }
    o << "  }\n";
  }
  if (floatingRoot()) {
    o << "  {  // free-flyer block: [[I, [h]x], [-[h]x, m 1]]\n"
         "    const double* h = d.ch[0].data();\n"
         "    const double hx[9] = {0.0, h[2], -h[1], -h[2], 0.0, h[0], h[1], -h[0], 0.0};\n"
         "    for (int j = 0; j < 3; ++j)\n"
         "      for (int i = 0; i < 3; ++i) {\n"
         "        M(i, j) = d.cI[0](i, j);\n"
         "        M(i, 3 + j) = hx[i + 3 * j];\n"
         "        M(3 + i, j) = -hx[i + 3 * j];\n"
         "        M(3 + i, 3 + j) = i == j ? d.cm[0] : 0.0;\n"
         "      }\n  }\n";
  }
  o << "}\n\n";
}

// Chain walks shared by CRBA, the Jacobians and the regressor: S6 holds each body's joint
// motion subspace (angular; linear) so a column needs no branch on the joint type.
void Emitter::emitChainTables(std::ostream& o) const {
  o << "constexpr double S6[" << nb_ << "][6] = {";
  for (int b = 0; b < nb_; ++b) {
    const TreeJoint& j = t_.bodies[idx(b)].joint;
    double s[6] = {0, 0, 0, 0, 0, 0};
    if (j.kind == JointKind::Revolute)
      for (int k = 0; k < 3; ++k) s[k] = j.axis(k);
    if (j.kind == JointKind::Prismatic)
      for (int k = 0; k < 3; ++k) s[3 + k] = j.axis(k);
    o << (b ? ",\n    " : "\n    ") << "{";
    for (int k = 0; k < 6; ++k) o << (k ? ", " : "") << literal(s[k]);
    o << "}";
  }
  o << "};\n";
  auto list = [&](const char* type, const char* n, auto item) {
    o << "constexpr " << type << " " << n << "[" << nb_ << "] = {";
    for (int b = 0; b < nb_; ++b) o << (b ? ", " : "") << item(b);
    o << "};\n";
  };
  list("int", "vIndex", [&](int b) { return str(b == 0 ? -1 : t_.bodies[idx(b)].joint.v_index); });
  list("double", "gain", [&](int b) { return literal(t_.bodies[idx(b)].joint.multiplier); });
  list("int", "parentOf", [&](int b) { return str(t_.bodies[idx(b)].parent); });
  std::vector<double> msub(idx(nb_), 0.0);
  for (int b = nb_ - 1; b >= 0; --b) {
    msub[idx(b)] += t_.bodies[idx(b)].inertia.mass;
    if (t_.bodies[idx(b)].parent >= 0) msub[idx(t_.bodies[idx(b)].parent)] += msub[idx(b)];
  }
  list("double", "subtreeMass", [&](int b) { return literal(msub[idx(b)]); });
  o << "constexpr double bodyMass[" << nb_ << "] = {";
  for (int b = 0; b < nb_; ++b) o << (b ? ", " : "") << literal(t_.bodies[idx(b)].inertia.mass);
  o << "};\n";
  o << "constexpr double bodyRotationalInertia[" << nb_ << "][9] = {";
  for (int b = 0; b < nb_; ++b) {
    const Matrix3d& I = t_.bodies[idx(b)].inertia.I;
    o << (b ? ",\n    " : "\n    ") << "{";
    for (int k = 0; k < 9; ++k) o << (k ? ", " : "") << literal(I(k % 3, k / 3));
    o << "}";
  }
  o << "};\n";
  o << "constexpr double bodyFirstMoment[" << nb_ << "][3] = {";
  for (int b = 0; b < nb_; ++b) {
    const Vector3d& h = t_.bodies[idx(b)].inertia.h;
    o << (b ? ", " : "") << "{" << literal(h(0)) << ", " << literal(h(1)) << ", " << literal(h(2)) << "}";
  }
  o << "};\n\n";
}

void Emitter::emitIntegrate(std::ostream& o) const {
  o << "void integrate(const ConfigVector& q, const TangentVector& v, double dt, ConfigVector& out) noexcept "
       "{\n"
       "  out = q;\n";
  for (int i = 0; i < static_cast<int>(t_.bodies.size()); ++i) {
    const TreeJoint& j = t_.bodies[idx(i)].joint;
    if ((j.kind == JointKind::Revolute || j.kind == JointKind::Prismatic) && !j.mimic)
      o << "  out(" << j.q_index << ") += v(" << j.v_index << ") * dt;\n";
  }
  if (floatingRoot()) {
    o << R"(  // base: SE(3) exponential of the body twist (ω, v)·dt
  const double w[3] = {v(0) * dt, v(1) * dt, v(2) * dt};
  const double u[3] = {v(3) * dt, v(4) * dt, v(5) * dt};
  const double th2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2], th = std::sqrt(th2);
  double B, C;  // (1−cos θ)/θ², (θ − sin θ)/θ³
  if (th < 1e-4) {
    B = 0.5 - th2 / 24.0;
    C = 1.0 / 6.0 - th2 / 120.0;
  } else {
    B = (1.0 - std::cos(th)) / th2;
    C = (th - std::sin(th)) / (th2 * th);
  }
  double wu[3], wwu[3], du[3];
  cross(w, u, wu);
  cross(w, wu, wwu);
  for (int i = 0; i < 3; ++i) du[i] = u[i] + B * wu[i] + C * wwu[i];
  const double n = std::sqrt(q(3) * q(3) + q(4) * q(4) + q(5) * q(5) + q(6) * q(6));
  const double qw = q(3) / n, qx = q(4) / n, qy = q(5) / n, qz = q(6) / n;
  const double R[9] = {1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy + qw * qz), 2 * (qx * qz - qw * qy),
                       2 * (qx * qy - qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz + qw * qx),
                       2 * (qx * qz + qw * qy), 2 * (qy * qz - qw * qx), 1 - 2 * (qx * qx + qy * qy)};
  double Rdu[3];
  rotate(R, du, Rdu);
  for (int i = 0; i < 3; ++i) out(i) = q(i) + Rdu[i];
  // quaternion of exp(w): (cos θ/2, sin(θ/2)/θ · w)
  const double dw = th < 1e-4 ? 1.0 - th2 / 8.0 : std::cos(0.5 * th);
  const double hs = th < 1e-4 ? 0.5 - th2 / 48.0 : std::sin(0.5 * th) / th;
  const double dx = hs * w[0], dy = hs * w[1], dz = hs * w[2];
  const double rw = qw * dw - qx * dx - qy * dy - qz * dz;
  const double rx = qw * dx + qx * dw + qy * dz - qz * dy;
  const double ry = qw * dy - qx * dz + qy * dw + qz * dx;
  const double rz = qw * dz + qx * dy - qy * dx + qz * dw;
  const double rn = std::sqrt(rw * rw + rx * rx + ry * ry + rz * rz);
  out(3) = rw / rn;
  out(4) = rx / rn;
  out(5) = ry / rn;
  out(6) = rz / rn;
)";
  } else {
    o << "  (void)dt;\n";
  }
  o << "}\n\n";
}

std::string Emitter::source() const {
  std::ostringstream o;
  o << "// Generated by mrqp-gen from " << origin_ << ". Do not edit: regenerate.\n"
    << "#include \"" << name_ << ".hpp\"\n\n#include <cmath>\n#include <cstring>\n#include <limits>\n\n"
    << "namespace " << name_ << " {\n\n"
    << "namespace {\nconstexpr double kInf = std::numeric_limits<double>::infinity();\n}  // namespace\n\n";
  emitTables(o);
  o << "namespace {\n\n" << runtimeKernels();
  emitLocalTransforms(o);
  emitForwardPass(o);
  emitBackwardTorques(o);
  emitChainTables(o);
  o << runtimeChainWalks() << "}  // namespace\n\n";
  o << "double totalMass() noexcept { return " << literal(t_.totalMass()) << "; }\n\n";
  o << runtimePublicFunctions();
  emitIntegrate(o);
  emitCrba(o);
  o << "}  // namespace " << name_ << "\n";
  return o.str();
}

}  // namespace

bool isValidModelName(const std::string& name) {
  static const std::set<std::string> keywords = {
      "alignas",  "alignof",   "and",      "asm",      "auto",      "bool",     "break",    "case",
      "catch",    "char",      "class",    "const",    "constexpr", "continue", "default",  "delete",
      "do",       "double",    "else",     "enum",     "explicit",  "export",   "extern",   "false",
      "float",    "for",       "friend",   "goto",     "if",        "inline",   "int",      "long",
      "mutable",  "namespace", "new",      "noexcept", "not",       "nullptr",  "operator", "or",
      "private",  "protected", "public",   "register", "return",    "short",    "signed",   "sizeof",
      "static",   "struct",    "switch",   "template", "this",      "throw",    "true",     "try",
      "typedef",  "typeid",    "typename", "union",    "unsigned",  "using",    "virtual",  "void",
      "volatile", "while",     "std",      "Eigen"};
  if (name.empty() || keywords.count(name)) return false;
  if (!(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

EmittedModel emitModel(const KinematicTree& tree, const std::string& name, const std::string& origin,
                       bool with_probe) {
  Emitter e(tree, name, origin);
  EmittedModel out;
  out.header = e.header();
  out.source = e.source();
  if (with_probe) out.probe = emitProbe(name, origin);
  return out;
}

}  // namespace mrqp::gen
