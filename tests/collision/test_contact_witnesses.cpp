// Several witnesses per pair (collision/contact_witnesses.hpp) against closed forms: the corners of
// the contact region of two boxes face to face (a small box over a large one: its bottom corners;
// two equal squares crossed at 45°: the eight crossings of their edges), of a box edge on a face,
// of parallel capsules (the overlap's ends), and the unique cases (vertex on face, crossed capsules)
// that get one witness. Every witness's distance is checked against the distance between its parts
// computed apart (a point against a box or a segment in closed form).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "collision/contact_witnesses.hpp"

using mrqp::collision::contactWitnesses;
using mrqp::collision::DistanceResult;
using mrqp::collision::PlacedShape;
using mrqp::collision::Shape;
using mrqp::collision::Witness;

namespace {

PlacedShape at(const Shape& s, const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  PlacedShape x;
  x.shape = &s;
  x.R = R;
  x.p = p;
  return x;
}

std::vector<Witness> witnesses(const PlacedShape& A, const PlacedShape& B) {
  DistanceResult r;
  REQUIRE(mrqp::collision::distance(A, B, &r));
  std::array<Witness, mrqp::collision::kMaxWitnesses> w;
  const int n = contactWitnesses(A, B, r, mrqp::collision::kWitnessBand, w.data(),
                                 mrqp::collision::kMaxWitnesses);
  REQUIRE(n >= 1);
  // The first is the nearest pair itself; every other is no nearer and within the band.
  CHECK(w[0].a.count == 0);
  CHECK(w[0].b.count == 0);
  for (int i = 1; i < n; ++i) {
    CHECK(w[static_cast<std::size_t>(i)].result.distance >= r.distance - 1e-12);
    CHECK(w[static_cast<std::size_t>(i)].result.distance <= r.distance + mrqp::collision::kWitnessBand);
  }
  return {w.begin(), w.begin() + n};
}

/// Closed form: distance from a point to an axis-aligned box of half extents h at c.
double pointBox(const Eigen::Vector3d& x, const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
  const Eigen::Vector3d d = ((x - c).cwiseAbs() - h).cwiseMax(0.0);
  return d.norm();
}

/// True when some witness has its point on A at `a` and on B at `b` (1e-9).
bool has(const std::vector<Witness>& w, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::any_of(w.begin(), w.end(), [&](const Witness& x) {
    return (x.result.a - a).norm() < 1e-9 && (x.result.b - b).norm() < 1e-9;
  });
}

}  // namespace

TEST_CASE("collision: a small box face down on a large box: the four corners of its face",
          "[collision]") {
  const Shape big = mrqp::collision::makeBox(Eigen::Vector3d(1.0, 1.0, 0.2));
  const Shape small = mrqp::collision::makeBox(Eigen::Vector3d(0.1, 0.06, 0.04));
  const double gap = 0.025;
  const Eigen::Vector3d c(0.13, -0.2, 0.1 + gap + 0.02);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const std::vector<Witness> w =
      witnesses(at(big, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()), at(small, R, c));
  // The nearest pair (somewhere on the face, or one of the corners) and the four corners.
  CHECK(w.size() >= 4);
  CHECK(w.size() <= 5);
  for (int sx = -1; sx <= 1; sx += 2) {
    for (int sy = -1; sy <= 1; sy += 2) {
      const Eigen::Vector3d corner = c + R * Eigen::Vector3d(0.05 * sx, 0.03 * sy, -0.02);
      INFO(sx << " " << sy);
      CHECK(has(w, Eigen::Vector3d(corner.x(), corner.y(), 0.1), corner));
    }
  }
  for (const Witness& x : w) CHECK(x.result.distance == Approx(gap).margin(1e-9));
}

TEST_CASE("collision: two equal squares crossed at 45°: the eight crossings of their edges", "[collision]") {
  const Shape plate = mrqp::collision::makeBox(Eigen::Vector3d(0.2, 0.2, 0.02));
  const double gap = 0.03;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d c(0.0, 0.0, 0.02 + gap);
  const PlacedShape A = at(plate, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
  const PlacedShape B = at(plate, R, c);
  const std::vector<Witness> w = witnesses(A, B);
  // The region is the regular octagon where the square |x|, |y| ≤ 0.1 meets its 45° turn: its
  // corners are at (±0.1, ±0.1 (√2 − 1)) and (±0.1 (√2 − 1), ±0.1): eight, with the nearest pair
  // (unless it is one of them) nine.
  CHECK(w.size() >= 8);
  CHECK(w.size() <= 9);
  const double t = 0.1 * (std::sqrt(2.0) - 1.0);
  int corners = 0;
  for (const auto& xy : std::array<Eigen::Vector2d, 8>{
           Eigen::Vector2d(0.1, t), Eigen::Vector2d(0.1, -t), Eigen::Vector2d(-0.1, t), Eigen::Vector2d(-0.1, -t),
           Eigen::Vector2d(t, 0.1), Eigen::Vector2d(-t, 0.1), Eigen::Vector2d(t, -0.1), Eigen::Vector2d(-t, -0.1)})
    corners += has(w, Eigen::Vector3d(xy.x(), xy.y(), 0.01), Eigen::Vector3d(xy.x(), xy.y(), 0.01 + gap)) ? 1 : 0;
  CHECK(corners == 8);
  for (const Witness& x : w) CHECK(x.result.distance == Approx(gap).margin(1e-9));
}

TEST_CASE("collision: a box edge on a face, parallel capsules: the ends of the contact segment",
          "[collision]") {
  SECTION("box edge on a box face, tilted within the band") {
    const Shape big = mrqp::collision::makeBox(Eigen::Vector3d(1.0, 1.0, 0.2));
    const Shape bar = mrqp::collision::makeBox(Eigen::Vector3d(0.2, 0.04, 0.04));
    // The bar turned 45° about its length (x): its lowest edge runs along x, 2 cm above the face;
    // and tilted by 0.004 rad about y so one end is 0.8 mm lower (within the band).
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.004, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    const Eigen::Vector3d c(0.0, 0.0, 0.1 + 0.02 + 0.02 * std::sqrt(2.0));
    const PlacedShape A = at(big, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    const PlacedShape B = at(bar, R, c);
    const std::vector<Witness> w = witnesses(A, B);
    // The lower edge's two ends, each against the face in closed form.
    int ends = 0;
    for (int s = -1; s <= 1; s += 2) {
      const Eigen::Vector3d end = c + R * Eigen::Vector3d(0.1 * s, -0.02, -0.02);
      const double d = end.z() - 0.1;
      for (const Witness& x : w) {
        if ((x.result.b - end).norm() < 1e-9) {
          ++ends;
          CHECK(x.result.distance == Approx(d).margin(1e-9));
          CHECK(x.result.distance == Approx(pointBox(end, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.5, 0.5, 0.1))).margin(1e-9));
        }
      }
    }
    CHECK(ends == 2);
  }
  SECTION("parallel capsules overlapping over part of their length") {
    const Shape cap = mrqp::collision::makeCapsule(0.05, 0.4);
    const Eigen::Matrix3d Rx = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    // Axes along x at y = 0 and y = 0.14; B shifted by 0.15 along x: the segments overlap on
    // x ∈ [−0.05, 0.2]; distance 0.14 − 0.1 = 0.04.
    const PlacedShape A = at(cap, Rx, Eigen::Vector3d::Zero());
    const PlacedShape B = at(cap, Rx, Eigen::Vector3d(0.15, 0.14, 0.0));
    const std::vector<Witness> w = witnesses(A, B);
    CHECK(has(w, Eigen::Vector3d(-0.05, 0.05, 0.0), Eigen::Vector3d(-0.05, 0.09, 0.0)));
    CHECK(has(w, Eigen::Vector3d(0.2, 0.05, 0.0), Eigen::Vector3d(0.2, 0.09, 0.0)));
    for (const Witness& x : w) CHECK(x.result.distance == Approx(0.04).margin(1e-9));
  }
}

TEST_CASE("collision: unique nearest points get one witness", "[collision]") {
  SECTION("a box corner down on a face") {
    const Shape big = mrqp::collision::makeBox(Eigen::Vector3d(1.0, 1.0, 0.2));
    const Shape small = mrqp::collision::makeBox(Eigen::Vector3d(0.1, 0.1, 0.1));
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitY()))
                                  .toRotationMatrix();
    CHECK(witnesses(at(big, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()),
                    at(small, R, Eigen::Vector3d(0.0, 0.0, 0.35)))
              .size() == 1);
  }
  SECTION("crossed capsules") {
    const Shape cap = mrqp::collision::makeCapsule(0.05, 0.4);
    const Eigen::Matrix3d Rx = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();
    const Eigen::Matrix3d Ry = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
    CHECK(witnesses(at(cap, Rx, Eigen::Vector3d::Zero()), at(cap, Ry, Eigen::Vector3d(0.02, -0.01, 0.13))).size() ==
          1);
  }
}
