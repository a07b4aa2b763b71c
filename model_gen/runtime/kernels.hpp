// Scalar kernels of every generated model (mrqp-gen copies the text after the marker line into
// the anonymous namespace of each generated .cpp): 3-vectors and rotations on raw pointers,
// spatial motion and force transforms (Featherstone), the body regressor of the inertial
// parameters; each marked [[maybe_unused]], since a model uses only the ones its tree needs.
// Plain scalar code rather than Eigen expressions: Eigen's product templates cost seconds of
// compile time per instantiation set, and every generated model would pay them.
// Compiled and tested on its own by tests/model_gen/test_runtime_kernels.cpp.
#pragma once

#include <cstddef>

// ---- mrqp-gen: the text below is copied into every generated model ----
/// The std::array position of a body or frame index (an int, >= 0 where it is used).
[[maybe_unused]] inline constexpr std::size_t ix(int i) noexcept { return static_cast<std::size_t>(i); }

/// out = R x (R column-major).
[[maybe_unused]] inline void rotate(const double* R, const double* x, double* out) noexcept {
  for (int i = 0; i < 3; ++i) out[i] = R[i] * x[0] + R[i + 3] * x[1] + R[i + 6] * x[2];
}

/// out = Rᵀ x.
[[maybe_unused]] inline void rotateT(const double* R, const double* x, double* out) noexcept {
  for (int i = 0; i < 3; ++i) out[i] = R[3 * i] * x[0] + R[3 * i + 1] * x[1] + R[3 * i + 2] * x[2];
}

[[maybe_unused]] inline void cross(const double* a, const double* b, double* out) noexcept {
  out[0] = a[1] * b[2] - a[2] * b[1];
  out[1] = a[2] * b[0] - a[0] * b[2];
  out[2] = a[0] * b[1] - a[1] * b[0];
}

/// out = X m: a parent motion in child coordinates, (Eᵀ ω, Eᵀ (v + ω × r)).
[[maybe_unused]] inline void motionToChild(const double* E, const double* r, const double* m,
                                           double* out) noexcept {
  const double l[3] = {m[3] + m[1] * r[2] - m[2] * r[1], m[4] + m[2] * r[0] - m[0] * r[2],
                       m[5] + m[0] * r[1] - m[1] * r[0]};
  rotateT(E, m, out);
  rotateT(E, l, out + 3);
}

/// out += X* f: a child wrench in parent coordinates, (E n + r × E f, E f).
[[maybe_unused]] inline void forceToParent(const double* E, const double* r, const double* f,
                                           double* out) noexcept {
  double en[3], ef[3];
  rotate(E, f, en);
  rotate(E, f + 3, ef);
  out[0] += en[0] + r[1] * ef[2] - r[2] * ef[1];
  out[1] += en[1] + r[2] * ef[0] - r[0] * ef[2];
  out[2] += en[2] + r[0] * ef[1] - r[1] * ef[0];
  out[3] += ef[0];
  out[4] += ef[1];
  out[5] += ef[2];
}

/// Body wrench I a + v ×* I v as a linear map of φ = (m, h, Ixx, Ixy, Iyy, Ixz, Iyz, Izz):
/// A is 6×10, row-major.
[[maybe_unused]] inline void bodyRegressor(const double* v, const double* a, double A[6][10]) noexcept {
  const double* w = v;
  const double* vl = v + 3;
  const double* al = a;      // angular acceleration
  const double* ll = a + 3;  // linear acceleration
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 10; ++k) A[i][k] = 0.0;
  double wxv[3];
  cross(w, vl, wxv);
  for (int i = 0; i < 3; ++i) A[3 + i][0] = ll[i] + wxv[i];
  // h columns: angular −[ll]× − [w]×[vl]× + [vl]×[w]× = −[ll]× − [w × vl]×; linear [al]× + [w]×[w]×
  const double c[3] = {ll[0] + wxv[0], ll[1] + wxv[1], ll[2] + wxv[2]};
  const double cx[3][3] = {{0.0, -c[2], c[1]}, {c[2], 0.0, -c[0]}, {-c[1], c[0], 0.0}};
  const double ax[3][3] = {{0.0, -al[2], al[1]}, {al[2], 0.0, -al[0]}, {-al[1], al[0], 0.0}};
  const double ww[3][3] = {{-(w[1] * w[1] + w[2] * w[2]), w[0] * w[1], w[0] * w[2]},
                           {w[0] * w[1], -(w[0] * w[0] + w[2] * w[2]), w[1] * w[2]},
                           {w[0] * w[2], w[1] * w[2], -(w[0] * w[0] + w[1] * w[1])}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      A[i][1 + j] = -cx[i][j];
      A[3 + i][1 + j] = ax[i][j] + ww[i][j];
    }
  // inertia columns: L(al) + [w]× L(w), L(x) = [[x0, x1, 0, x2, 0, 0], [0, x0, x1, 0, x2, 0], [0, 0, 0, x0, x1, x2]]
  const double Lw[3][6] = {{w[0], w[1], 0.0, w[2], 0.0, 0.0},
                           {0.0, w[0], w[1], 0.0, w[2], 0.0},
                           {0.0, 0.0, 0.0, w[0], w[1], w[2]}};
  const double La[3][6] = {{al[0], al[1], 0.0, al[2], 0.0, 0.0},
                           {0.0, al[0], al[1], 0.0, al[2], 0.0},
                           {0.0, 0.0, 0.0, al[0], al[1], al[2]}};
  for (int k = 0; k < 6; ++k) {
    const double col[3] = {Lw[0][k], Lw[1][k], Lw[2][k]};
    double wc[3];
    cross(w, col, wc);
    for (int i = 0; i < 3; ++i) A[i][4 + k] = La[i][k] + wc[i];
  }
}
