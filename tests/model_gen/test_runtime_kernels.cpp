// The scalar kernels every generated model carries (model_gen/runtime/kernels.hpp), compiled here
// on their own and checked against Eigen: rotations and cross products directly, the motion and
// force transforms by the invariance of power (m·f in one frame equals m·f in the other), pose
// composition, and the body regressor against the spatial-inertia form I a + v ×* I v.
#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <random>

#include "kernels.hpp"

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;

struct Rng {
  std::mt19937 gen{12345u};
  std::uniform_real_distribution<double> u{-1.0, 1.0};
  double operator()() { return u(gen); }
  Vector3d vec3() { return Vector3d((*this)(), (*this)(), (*this)()); }
  Vector6d vec6() {
    Vector6d v;
    for (int i = 0; i < 6; ++i) v(i) = (*this)();
    return v;
  }
  Matrix3d rotation() {
    Eigen::Quaterniond q((*this)(), (*this)(), (*this)(), (*this)());
    return q.normalized().toRotationMatrix();
  }
};

Matrix3d skew(const Vector3d& a) {
  Matrix3d s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

}  // namespace

TEST_CASE("model kernels: rotations and cross products equal Eigen's", "[model_gen][kernels]") {
  Rng rng;
  for (int k = 0; k < 20; ++k) {
    const Matrix3d R = rng.rotation();
    const Vector3d x = rng.vec3(), y = rng.vec3();
    Vector3d out;
    rotate(R.data(), x.data(), out.data());
    CHECK((out - R * x).norm() < 1e-15);
    rotateT(R.data(), x.data(), out.data());
    CHECK((out - R.transpose() * x).norm() < 1e-15);
    cross(x.data(), y.data(), out.data());
    CHECK((out - x.cross(y)).norm() < 1e-15);
  }
}

TEST_CASE("model kernels: motion and force transforms keep power invariant", "[model_gen][kernels]") {
  Rng rng;
  for (int k = 0; k < 20; ++k) {
    const Matrix3d E = rng.rotation();  // child orientation in the parent
    const Vector3d r = rng.vec3();      // child origin in the parent
    const Vector6d m_parent = rng.vec6(), f_child = rng.vec6();
    Vector6d m_child;
    motionToChild(E.data(), r.data(), m_parent.data(), m_child.data());
    // (Eᵀ ω, Eᵀ (v + ω × r)) directly.
    const Vector3d w = m_parent.head<3>(), v = m_parent.tail<3>();
    CHECK((m_child.head<3>() - E.transpose() * w).norm() < 1e-14);
    CHECK((m_child.tail<3>() - E.transpose() * (v + w.cross(r))).norm() < 1e-14);
    Vector6d f_parent = Vector6d::Zero();
    forceToParent(E.data(), r.data(), f_child.data(), f_parent.data());
    CHECK(std::abs(m_child.dot(f_child) - m_parent.dot(f_parent)) < 1e-14);
    // ... and it accumulates.
    Vector6d twice = f_parent;
    forceToParent(E.data(), r.data(), f_child.data(), twice.data());
    CHECK((twice - 2.0 * f_parent).norm() < 1e-14);
  }
}

TEST_CASE("model kernels: the body regressor times the parameters is I a + v x* I v",
          "[model_gen][kernels]") {
  Rng rng;
  for (int k = 0; k < 20; ++k) {
    const double m = 1.0 + std::abs(rng());
    const Vector3d h = rng.vec3();
    Matrix3d I = Matrix3d::Random();
    I = I * I.transpose() + Matrix3d::Identity();  // symmetric
    Eigen::Matrix<double, 6, 6> I6;                // spatial inertia about the origin, (angular; linear)
    I6 << I, skew(h), skew(h).transpose(), m * Matrix3d::Identity();
    const Vector6d v = rng.vec6(), a = rng.vec6();
    const Vector6d Iv = I6 * v;
    Vector6d vxIv;  // v ×* (I v)
    vxIv << v.head<3>().cross(Iv.head<3>()) + v.tail<3>().cross(Iv.tail<3>()),
        v.head<3>().cross(Iv.tail<3>());
    const Vector6d expected = I6 * a + vxIv;

    double A[6][10];
    bodyRegressor(v.data(), a.data(), A);
    Eigen::Matrix<double, 10, 1> phi;
    phi << m, h, I(0, 0), I(0, 1), I(1, 1), I(0, 2), I(1, 2), I(2, 2);
    Vector6d got;
    for (int i = 0; i < 6; ++i) {
      got(i) = 0.0;
      for (int j = 0; j < 10; ++j) got(i) += A[i][j] * phi(j);
    }
    CHECK((got - expected).norm() < 1e-12 * (1.0 + expected.norm()));
  }
}

TEST_CASE("model kernels: ix() is the std::array position of an index", "[model_gen][kernels]") {
  CHECK(ix(0) == std::size_t{0});
  CHECK(ix(41) == std::size_t{41});
}
