// One generic face for the generated model namespaces, so a test can be written once as a template.
#pragma once

#define MRQP_MODEL_ADAPTER(NS)                                                                   \
  struct NS##_adapter {                                                                          \
    static constexpr int nq = NS::nq, nv = NS::nv, nbodies = NS::nbodies, nframes = NS::nframes; \
    static constexpr bool floating_base = NS::floating_base;                                     \
    using Data = NS::Data;                                                                       \
    using ConfigVector = NS::ConfigVector;                                                       \
    using TangentVector = NS::TangentVector;                                                     \
    using MassMatrix = NS::MassMatrix;                                                           \
    using Jacobian = NS::Jacobian;                                                               \
    using ComJacobian = NS::ComJacobian;                                                         \
    using Regressor = NS::Regressor;                                                             \
    using ParamVector = NS::ParamVector;                                                         \
    using Pose = NS::Pose;                                                                       \
    using ReferenceFrame = NS::ReferenceFrame;                                                   \
    static const auto& jointNames() { return NS::joint_names; }                                  \
    static const auto& frameNames() { return NS::frame_names; }                                  \
    static const auto& qLower() { return NS::q_lower; }                                          \
    static const auto& qUpper() { return NS::q_upper; }                                          \
    static const auto& vLimit() { return NS::v_limit; }                                          \
    static const auto& effortLimit() { return NS::effort_limit; }                                \
    static double totalMass() { return NS::totalMass(); }                                        \
    static int frameIndex(const char* n) { return NS::frameIndex(n); }                           \
    static void neutral(ConfigVector& q) { NS::neutral(q); }                                     \
    static void integrate(const ConfigVector& q, const TangentVector& v, double dt,             \
                          ConfigVector& o) {                                                     \
      NS::integrate(q, v, dt, o);                                                                \
    }                                                                                            \
    static void fk(Data& d, const ConfigVector& q) { NS::forwardKinematics(d, q); }              \
    static void fk(Data& d, const ConfigVector& q, const TangentVector& v) {                     \
      NS::forwardKinematics(d, q, v);                                                            \
    }                                                                                            \
    static Pose framePose(const Data& d, int f) { return NS::framePose(d, f); }                  \
    static void jacobian(const Data& d, int f, const Eigen::Vector3d& p, bool world,            \
                         Jacobian& J) {                                                          \
      NS::frameJacobian(d, f, p, world ? ReferenceFrame::WorldAligned : ReferenceFrame::Local,   \
                        J);                                                                      \
    }                                                                                            \
    static NS::Motion bias(const Data& d, int f, const Eigen::Vector3d& p, bool world) {         \
      return NS::frameBiasAcceleration(                                                          \
          d, f, p, world ? ReferenceFrame::WorldAligned : ReferenceFrame::Local);                \
    }                                                                                            \
    static Eigen::Vector3d com(const Data& d) { return NS::centerOfMass(d); }                    \
    static void comJacobian(Data& d, ComJacobian& J) { NS::comJacobian(d, J); }                  \
    static void crba(Data& d, const ConfigVector& q, MassMatrix& M) { NS::crba(d, q, M); }       \
    static void nle(Data& d, const ConfigVector& q, const TangentVector& v, TangentVector& N) {   \
      NS::nonLinearEffects(d, q, v, N);                                                          \
    }                                                                                            \
    static void rnea(Data& d, const ConfigVector& q, const TangentVector& v,                    \
                     const TangentVector& a, TangentVector& t) {                                 \
      NS::rnea(d, q, v, a, t);                                                                   \
    }                                                                                            \
    static void regressor(Data& d, const ConfigVector& q, const TangentVector& v,               \
                          const TangentVector& a, Regressor& Y) {                                \
      NS::regressor(d, q, v, a, Y);                                                              \
    }                                                                                            \
    static void params(ParamVector& p) { NS::inertialParameters(p); }                            \
  }
