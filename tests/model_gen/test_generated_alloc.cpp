// Every generated function, called 10,000 times, allocates nothing: the global allocator is
// replaced by a counting one (operator new and malloc), and Eigen is built with
// EIGEN_RUNTIME_NO_MALLOC and told that allocation is forbidden during the calls.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <memory>
#include <new>

#include "counting_allocator.hpp"
#include "jvrc1_model.hpp"
#include "panda_model.hpp"
#include "romeo_model.hpp"

namespace {

/// Counts the allocations made by `body` called `n` times, with Eigen's allocation forbidden.
template <class F>
long allocationsDuring(int n, F&& body) {
  return mrqp::testing::allocationsIn([&] {
    for (int i = 0; i < n; ++i) body(i);
  });
}

#define MRQP_ALLOC_CHECK(NS)                                                                                 \
  do {                                                                                                       \
    auto d = std::make_unique<NS::Data>();                                                                   \
    auto M = std::make_unique<NS::MassMatrix>();                                                             \
    auto Y = std::make_unique<NS::Regressor>();                                                              \
    Y->resize(NS::nv, NS::nparams);                                                                          \
    auto J = std::make_unique<NS::Jacobian>();                                                               \
    auto Jc = std::make_unique<NS::ComJacobian>();                                                           \
    auto phi = std::make_unique<NS::ParamVector>();                                                          \
    NS::ConfigVector q, q2;                                                                                  \
    NS::neutral(q);                                                                                          \
    NS::TangentVector v = NS::TangentVector::Constant(0.1), a = NS::TangentVector::Constant(0.2);            \
    NS::TangentVector tau, N;                                                                                \
    const Eigen::Vector3d pt(0.01, 0.02, 0.03);                                                              \
    double sink = 0.0;                                                                                       \
    const int n = 10000;                                                                                     \
    CHECK(allocationsDuring(n, [&](int) { NS::forwardKinematics(*d, q); }) == 0);                            \
    CHECK(allocationsDuring(n, [&](int) { NS::forwardKinematics(*d, q, v); }) == 0);                         \
    CHECK(allocationsDuring(n, [&](int i) { sink += NS::framePose(*d, i % NS::nframes).p(0); }) == 0);       \
    CHECK(allocationsDuring(n, [&](int i) {                                                                  \
            NS::frameJacobian(*d, i % NS::nframes, pt,                                                       \
                              i % 2 ? NS::ReferenceFrame::Local : NS::ReferenceFrame::WorldAligned, *J);     \
          }) == 0);                                                                                          \
    CHECK(allocationsDuring(n, [&](int i) {                                                                  \
            sink += NS::frameBiasAcceleration(*d, i % NS::nframes, pt, NS::ReferenceFrame::WorldAligned)(0); \
          }) == 0);                                                                                          \
    CHECK(allocationsDuring(n, [&](int) { sink += NS::centerOfMass(*d)(0); }) == 0);                         \
    CHECK(allocationsDuring(n, [&](int) { NS::comJacobian(*d, *Jc); }) == 0);                                \
    CHECK(allocationsDuring(n, [&](int) { NS::crba(*d, q, *M); }) == 0);                                     \
    CHECK(allocationsDuring(n, [&](int) { NS::nonLinearEffects(*d, q, v, N); }) == 0);                       \
    CHECK(allocationsDuring(n, [&](int) { NS::rnea(*d, q, v, a, tau); }) == 0);                              \
    CHECK(allocationsDuring(n, [&](int) { NS::regressor(*d, q, v, a, *Y); }) == 0);                          \
    CHECK(allocationsDuring(n, [&](int) { NS::inertialParameters(*phi); }) == 0);                            \
    CHECK(allocationsDuring(n, [&](int) { NS::integrate(q, v, 1e-3, q2); }) == 0);                           \
    CHECK(allocationsDuring(n, [&](int) { NS::neutral(q2); }) == 0);                                         \
    CHECK(allocationsDuring(n, [&](int) { sink += NS::frameIndex("no such frame"); }) == 0);                 \
    CHECK(std::isfinite(sink));                                                                              \
  } while (false)

}  // namespace

TEST_CASE("the counting allocator sees allocations", "[model_gen][realtime]") {
  // the test would be vacuous if the replacement were not in effect
  static void* volatile sink;  // keeps the compiler from eliding the pairs below
  CHECK(allocationsDuring(3, [](int) {
          sink = ::operator new(4);
          ::operator delete(sink);
        }) == 3);
  CHECK(allocationsDuring(2, [](int) {
          sink = std::malloc(16);
          std::free(sink);
        }) == 2);
}

TEST_CASE("generated Panda functions do not allocate", "[model_gen][realtime]") {
  MRQP_ALLOC_CHECK(panda_model);
}

TEST_CASE("generated JVRC-1 (free-flyer) functions do not allocate", "[model_gen][realtime]") {
  MRQP_ALLOC_CHECK(jvrc1_model);
}

TEST_CASE("generated Romeo functions do not allocate", "[model_gen][realtime]") {
  MRQP_ALLOC_CHECK(romeo_model);
}
