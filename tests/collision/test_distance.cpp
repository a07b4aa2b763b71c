// Distances and witness points of control/collision against closed forms: sphere–sphere,
// sphere–box (the clamped centre), box–box with face, edge and vertex nearest features,
// capsule–capsule (Ericson's segment–segment closest points), a hull against the exact
// point–triangle distance to each of its faces; penetration signs; libccd's margin reading.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "collision/distance.hpp"
#include "collision/shape.hpp"
#include "hull_faces.hpp"

using namespace mrqp::collision;
using Eigen::Vector3d;

namespace {

constexpr double kTol = 1e-6;

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized().toRotationMatrix();
}

PlacedShape at(const Shape& s, const Eigen::Matrix3d& R, const Vector3d& p) { return place(s, R, p); }

// The witnesses lie on their shapes' surfaces, are `distance` apart along the normal.
void checkWitnesses(const DistanceResult& r) {
  CHECK((r.b - r.a).norm() == Approx(std::abs(r.distance)).margin(kTol));
  CHECK(r.normal.norm() == Approx(1.0).margin(1e-12));
  CHECK(r.normal.dot(r.b - r.a) == Approx(r.distance).margin(kTol));
}

// Closest points of segments p1q1 and p2q2 (Ericson, Real-Time Collision Detection, 5.1.9).
double segmentDistance(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2, const Vector3d& q2) {
  const Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  const double c = d1.dot(r), b = d1.dot(d2), denom = a * e - b * b;
  s = denom > 1e-300 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return ((p1 + s * d1) - (p2 + t * d2)).norm();
}

}  // namespace

TEST_CASE("collision: Sphere–sphere: distance, witnesses and penetration against the closed form",
          "[collision]") {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0), ur(0.01, 0.3);
  for (int k = 0; k < 200; ++k) {
    const Shape a = makeSphere(ur(rng)), b = makeSphere(ur(rng));
    const Vector3d ca(u(rng), u(rng), u(rng)), cb(u(rng), u(rng), u(rng));
    DistanceResult r;
    REQUIRE(distance(at(a, randomRotation(rng), ca), at(b, randomRotation(rng), cb), &r));
    const double expected = (cb - ca).norm() - a.radius - b.radius;
    CHECK(r.distance == Approx(expected).margin(kTol));
    CHECK((r.a - (ca + a.radius * (cb - ca).normalized())).norm() < kTol);
    CHECK((r.b - (cb - b.radius * (cb - ca).normalized())).norm() < kTol);
    checkWitnesses(r);
  }
}

TEST_CASE("collision: Sphere–box: distance to the clamped centre", "[collision]") {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0), us(0.05, 0.8), ur(0.0, 0.2);
  int outside = 0;
  for (int k = 0; k < 400; ++k) {
    const Shape box = makeBox(Vector3d(us(rng), us(rng), us(rng)));
    const Shape s = makeSphere(ur(rng));
    const Eigen::Matrix3d R = randomRotation(rng);
    const Vector3d p(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vector3d cl = R.transpose() * (c - p);
    const Vector3d clamped = cl.cwiseMax(-box.half).cwiseMin(box.half);
    const double dc = (cl - clamped).norm();
    if (dc < 1e-3) continue;  // centre inside the box: no closed form here
    ++outside;
    DistanceResult r;
    REQUIRE(distance(at(box, R, p), at(s, Eigen::Matrix3d::Identity(), c), &r));
    CHECK(r.distance == Approx(dc - s.radius).margin(kTol));
    CHECK((r.a - (R * clamped + p)).norm() < kTol);
    checkWitnesses(r);
  }
  CHECK(outside > 200);
}

TEST_CASE("collision: Box–box: face, edge and vertex nearest features", "[collision]") {
  const Shape A = makeBox(Vector3d(0.4, 0.6, 0.8));  // half (0.2, 0.3, 0.4)
  const Shape B = makeBox(Vector3d(0.1, 0.1, 0.1));  // half 0.05
  const Shape C = makeBox(Vector3d(0.2, 0.2, 0.2));  // half 0.1
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d Ry = Eigen::AngleAxisd(M_PI / 4, Vector3d::UnitY()).toRotationMatrix();
  // B's corner (−h, −h, −h) turned onto −x: it reaches h√3 from B's centre.
  const Eigen::Matrix3d Rv =
      Eigen::Quaterniond::FromTwoVectors(Vector3d(-1.0, -1.0, -1.0).normalized(), -Vector3d::UnitX())
          .toRotationMatrix();
  const double h = 0.05, reach = 0.1 * std::sqrt(2.0);
  for (const double gap : {0.3, 0.05, 1e-3, -0.01}) {
    const double tol = gap < 0.0 ? 1e-3 : kTol;  // penetration: libccd's MPR
    DistanceResult r;
    INFO("gap " << gap);
    // face–face
    REQUIRE(distance(at(A, I, Vector3d::Zero()), at(B, I, Vector3d(0.2 + gap + h, 0.01, -0.02)), &r));
    CHECK(r.distance == Approx(gap).margin(tol));
    CHECK(r.normal.x() == Approx(1.0).margin(1e-6));
    if (gap > 0.0) checkWitnesses(r);
    // edge–face
    REQUIRE(distance(at(A, I, Vector3d::Zero()),
                     at(B, Rz, Vector3d(0.2 + gap + h * std::sqrt(2.0), 0.0, 0.1)), &r));
    CHECK(r.distance == Approx(gap).margin(tol));
    if (gap > 0.0) checkWitnesses(r);
    // vertex–face
    REQUIRE(distance(at(A, I, Vector3d::Zero()),
                     at(B, Rv, Vector3d(0.2 + gap + h * std::sqrt(3.0), 0.1, 0.0)), &r));
    CHECK(r.distance == Approx(gap).margin(tol));
    if (gap > 0.0) {
      checkWitnesses(r);
      CHECK((r.b - Vector3d(0.2 + gap, 0.1, 0.0)).norm() < kTol);
    }
    // edge–edge, crossed: C's edge along z at x = 0.1√2, B's edge along y
    REQUIRE(distance(at(C, Rz, Vector3d::Zero()),
                     at(B, Ry, Vector3d(reach + gap + h * std::sqrt(2.0), 0.0, 0.0)), &r));
    CHECK(r.distance == Approx(gap).margin(tol));
    if (gap > 0.0) {
      checkWitnesses(r);
      CHECK((r.a - Vector3d(reach, 0.0, 0.0)).norm() < kTol);
      CHECK((r.b - Vector3d(reach + gap, 0.0, 0.0)).norm() < kTol);
    }
  }
}

TEST_CASE("collision: Capsule–capsule against the segment–segment closest points", "[collision]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.6, 0.6), ul(0.0, 0.5), ur(0.01, 0.1);
  int separated = 0;
  for (int k = 0; k < 500; ++k) {
    const Shape a = makeCapsule(ur(rng), ul(rng)), b = makeCapsule(ur(rng), ul(rng));
    const Eigen::Matrix3d Ra = randomRotation(rng), Rb = randomRotation(rng);
    const Vector3d pa(u(rng), u(rng), u(rng)), pb(u(rng), u(rng), u(rng));
    const Vector3d ea = Ra.col(2) * a.half.z(), eb = Rb.col(2) * b.half.z();
    const double seg = segmentDistance(pa - ea, pa + ea, pb - eb, pb + eb);
    if (seg < 1e-4) continue;  // axes meet: the distance is −(radii) only up to MPR's precision
    DistanceResult r;
    REQUIRE(distance(at(a, Ra, pa), at(b, Rb, pb), &r));
    CHECK(r.distance == Approx(seg - a.radius - b.radius).margin(kTol));
    checkWitnesses(r);
    if (r.distance > 0.0) ++separated;
  }
  CHECK(separated > 200);
  SECTION("crossing perpendicular capsules") {
    const Shape c = makeCapsule(0.05, 1.0);
    const Eigen::Matrix3d Rx = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY()).toRotationMatrix();
    DistanceResult r;
    REQUIRE(distance(at(c, Eigen::Matrix3d::Identity(), Vector3d::Zero()), at(c, Rx, Vector3d(0.0, 0.3, 0.1)),
                     &r));
    CHECK(r.distance == Approx(0.3 - 0.1).margin(kTol));
  }
}

TEST_CASE("collision: Hull–sphere against the exact distance to every hull face", "[collision]") {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0), ur(0.0, 0.1);
  for (int k = 0; k < 40; ++k) {
    std::vector<Vector3d> pts;
    for (int i = 0; i < 60; ++i) pts.emplace_back(0.3 * u(rng), 0.2 * u(rng), 0.25 * u(rng));
    const mrqp::testing::HullFaces hull = mrqp::testing::hullFaces(pts);
    const Shape h = makeHull(hull.vertices.data(), static_cast<int>(hull.vertices.size()));
    for (int j = 0; j < 10; ++j) {
      const Vector3d c = 0.8 * Vector3d(u(rng), u(rng), u(rng));
      const double ref = mrqp::testing::pointHullDistance(hull, c);
      if (ref < 1e-3) continue;  // inside
      const Shape s = makeSphere(ur(rng));
      const Eigen::Matrix3d R = randomRotation(rng);
      const Vector3d p(u(rng), u(rng), u(rng));
      DistanceResult r;
      REQUIRE(distance(at(h, R, p), at(s, Eigen::Matrix3d::Identity(), R * c + p), &r));
      CHECK(r.distance == Approx(ref - s.radius).margin(kTol));
      checkWitnesses(r);
    }
  }
}

TEST_CASE("collision: Overlapping cores: negative distance from libccd's MPR", "[collision]") {
  const Shape a = makeBox(Vector3d(0.2, 0.2, 0.2)), b = makeSphere(0.05);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  DistanceResult r;
  REQUIRE(distance(at(a, I, Vector3d::Zero()), at(b, I, Vector3d(0.08, 0.0, 0.0)), &r));
  CHECK(r.penetrating);
  CHECK(r.distance == Approx(-(0.1 - 0.08 + 0.05)).margin(1e-4));
  CHECK(r.normal.x() == Approx(1.0).margin(1e-3));
  // Two spheres with centres 0.05 apart and radii 0.1: MPR along the centres is exact.
  const Shape s = makeSphere(0.1);
  REQUIRE(distance(at(s, I, Vector3d::Zero()), at(s, I, Vector3d(0.0, 0.05, 0.0)), &r));
  CHECK(r.distance == Approx(0.05 - 0.2).margin(1e-6));
  CHECK(r.normal.y() == Approx(1.0).margin(1e-6));
}

TEST_CASE("collision: libccd with margins: closerThan is exact, margins − MPR depth a lower bound",
          "[collision]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 0.5), us(0.05, 0.3);
  int close = 0;
  double worst = 0.0;
  for (int k = 0; k < 300; ++k) {
    const Shape a = makeBox(Vector3d(us(rng), us(rng), us(rng))), b = makeCapsule(0.05, us(rng));
    const PlacedShape A = at(a, randomRotation(rng), Vector3d(u(rng), u(rng), u(rng)));
    const PlacedShape B = at(b, randomRotation(rng), Vector3d(u(rng), u(rng), u(rng)));
    DistanceResult exact;
    REQUIRE(distance(A, B, &exact));
    if (exact.distance <= 0.0) continue;
    const double delta = 0.2;
    if (std::abs(exact.distance - delta) > 1e-6) CHECK(closerThan(A, B, delta) == (exact.distance < delta));
    DistanceResult m;
    if (marginDistance(A, B, 0.5 * delta, &m)) {
      ++close;
      CHECK(m.distance <= exact.distance + 1e-6);
      worst = std::max(worst, exact.distance - m.distance);
    } else {
      CHECK(exact.distance >= delta - 1e-6);
    }
  }
  CHECK(close > 20);
  WARN("largest error of margins − MPR depth below the exact distance: " << worst << " m");
}
