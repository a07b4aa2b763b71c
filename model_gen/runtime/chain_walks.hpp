// Algorithms of every generated model that walk its tables (S6, vIndex, gain, parentOf,
// subtreeMass, bodyMass, bodyFirstMoment, bodyRotationalInertia, frame_R, frame_p) and its Data:
// mrqp-gen copies the text after the marker line into the anonymous namespace of each generated
// .cpp, after the model's tables and kernels.hpp. Compiled in every generated model and tested
// there against the reference implementation (tests/model_gen/test_generated_models.cpp).
#pragma once

// ---- mrqp-gen: the text below is copied into every generated model ----
/// A joint's motion subspace S6[b] classified once, at compile time: revolute (part 0: the axis is
/// the angular half), prismatic (part 3) or none (−1, the root); when the axis is ±e_k of the body
/// frame (most robots), its world direction is ±column k of R_b and needs no arithmetic.
struct JointAxis {
  int part;
  int column;  ///< k when the axis is ±e_k, else −1
  double sign;
};

constexpr std::array<JointAxis, nbodies> makeJointAxes() noexcept {
  std::array<JointAxis, nbodies> out{};
  for (int b = 0; b < nbodies; ++b) {
    JointAxis a{-1, -1, 1.0};
    for (int part = 0; part <= 3; part += 3)
      if (S6[b][part] != 0.0 || S6[b][part + 1] != 0.0 || S6[b][part + 2] != 0.0) a.part = part;
    if (a.part >= 0) {
      int nonzero = 0;
      for (int k = 0; k < 3; ++k)
        if (S6[b][a.part + k] != 0.0) {
          ++nonzero;
          a.column = k;
          a.sign = S6[b][a.part + k];
        }
      if (nonzero != 1 || (a.sign != 1.0 && a.sign != -1.0)) {
        a.column = -1;
        a.sign = 1.0;
      }
    }
    out[ix(b)] = a;
  }
  return out;
}
constexpr std::array<JointAxis, nbodies> jointAxes = makeJointAxes();

/// World direction of body b's joint axis, R_b a.
inline void jointAxisWorld(const Data& d, int b, double* out) noexcept {
  const JointAxis& j = jointAxes[ix(b)];
  const double* R = d.R[ix(b)].data();
  if (j.column >= 0) {
    const double* col = R + 3 * j.column;
    for (int i = 0; i < 3; ++i) out[i] = j.sign * col[i];
  } else {
    rotate(R, S6[b] + (j.part > 0 ? j.part : 0), out);
  }
}

/// World-aligned Jacobian columns of the world point pt carried by body b (added to J): a revolute
/// joint c gives (a, a × (pt − p_c)), a prismatic one (0, a), a = R_c's joint axis.
inline void bodyJacobian(const Data& d, int b, const double* pt, Jacobian& J) noexcept {
  double* Jp = J.data();
  for (int c = b; c > 0; c = parentOf[c]) {
    double a[3];
    jointAxisWorld(d, c, a);
    double* col = Jp + 6 * vIndex[c];
    const double g = gain[c];
    if (jointAxes[ix(c)].part == 0) {
      const double* pc = d.p[ix(c)].data();
      const double dp[3] = {pt[0] - pc[0], pt[1] - pc[1], pt[2] - pc[2]};
      col[0] += g * a[0];
      col[1] += g * a[1];
      col[2] += g * a[2];
      col[3] += g * (a[1] * dp[2] - a[2] * dp[1]);
      col[4] += g * (a[2] * dp[0] - a[0] * dp[2]);
      col[5] += g * (a[0] * dp[1] - a[1] * dp[0]);
    } else {
      col[3] += g * a[0];
      col[4] += g * a[1];
      col[5] += g * a[2];
    }
  }
  if (floating_base) {
    const double* R0 = d.R[0].data();
    double dp[3];
    for (int i = 0; i < 3; ++i) dp[i] = pt[i] - d.p[0][i];
    for (int k = 0; k < 3; ++k) {
      double lin[3];
      cross(R0 + 3 * k, dp, lin);  // −[dp]× R0 e_k
      for (int i = 0; i < 3; ++i) {
        Jp[6 * k + i] += R0[3 * k + i];
        Jp[6 * k + 3 + i] += lin[i];
        Jp[6 * (3 + k) + 3 + i] += R0[3 * k + i];
      }
    }
  }
}

/// A frame's placement on its body and a point given in the frame, in body coordinates.
inline void pointOnBody(int frame, const double* point, double* r) noexcept {
  const double* Rf = frame_R[frame];
  for (int i = 0; i < 3; ++i)
    r[i] = frame_p[frame][i] + Rf[3 * i] * point[0] + Rf[3 * i + 1] * point[1] + Rf[3 * i + 2] * point[2];
}

/// x_frame = Rfᵀ x_body.
inline void bodyToFrame(int frame, const double* x, double* out) noexcept {
  const double* Rf = frame_R[frame];
  for (int i = 0; i < 3; ++i) out[i] = Rf[i] * x[0] + Rf[3 + i] * x[1] + Rf[6 + i] * x[2];
}

/// Composite-rigid-body algorithm in one frame, O: axes aligned with the world at the root's origin.
/// Each body's inertia is moved to O once (m, h, I about O); a body's composite is then the plain
/// sum of its subtree's, with no transform between a body and its parent; a joint is the Plücker
/// vector s_b = (w, r_b × w + u) at O (r_b = p_b − p_0; (w, u) = R_b S_b), F_b = I^C_b s_b and
/// M(v_c, v_b) = g_b g_c s_cᵀ F_b for b and each ancestor c with a joint. The free-flyer's columns
/// are F_b in root axes, and on return d.cm/ch/cI[0] hold the whole robot's inertia in root axes
/// at the root origin (the free-flyer block). Needs d.Rl, d.pl (localTransforms); sets d.R, d.p.
inline void crbaAtRoot(Data& d, MassMatrix& M) noexcept {
  worldPoses(d);
  double* Mp = M.data();
  const double* p0 = d.p[0].data();
  for (int b = 0; b < nbodies; ++b) {
    const double* E = d.R[ix(b)].data();
    const double r[3] = {d.p[ix(b)](0) - p0[0], d.p[ix(b)](1) - p0[1], d.p[ix(b)](2) - p0[2]};
    const double m = bodyMass[b];
    const double* I = bodyRotationalInertia[b];
    double Eh[3];
    rotate(E, bodyFirstMoment[b], Eh);
    double EI[9];  // E I, column-major
    for (int j = 0; j < 3; ++j) rotate(E, I + 3 * j, EI + 3 * j);
    const double rEh = r[0] * Eh[0] + r[1] * Eh[1] + r[2] * Eh[2];
    const double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    double* Io = d.cI[ix(b)].data();
    for (int j = 0; j < 3; ++j)
      for (int i = j; i < 3; ++i) {
        double x = EI[i] * E[j] + EI[i + 3] * E[j + 3] + EI[i + 6] * E[j + 6];  // (E I Eᵀ)(i, j)
        x -= Eh[i] * r[j] + r[i] * Eh[j] + m * r[i] * r[j];
        if (i == j) x += 2.0 * rEh + m * rr;
        Io[i + 3 * j] = x;
        Io[j + 3 * i] = x;
      }
    for (int i = 0; i < 3; ++i) d.ch[ix(b)](i) = Eh[i] + m * r[i];
    d.cm[ix(b)] = m;
  }
  for (int b = nbodies - 1; b > 0; --b) {
    const int p = parentOf[b];
    d.cm[ix(p)] += d.cm[ix(b)];
    d.ch[ix(p)] += d.ch[ix(b)];
    d.cI[ix(p)] += d.cI[ix(b)];
  }
  double S[nbodies][6];
  for (int b = 1; b < nbodies; ++b) {
    double a[3];
    jointAxisWorld(d, b, a);
    double* s = S[b];
    if (jointAxes[ix(b)].part == 0) {
      const double r[3] = {d.p[ix(b)](0) - p0[0], d.p[ix(b)](1) - p0[1], d.p[ix(b)](2) - p0[2]};
      s[0] = a[0];
      s[1] = a[1];
      s[2] = a[2];
      cross(r, a, s + 3);
    } else {
      s[0] = s[1] = s[2] = 0.0;
      s[3] = a[0];
      s[4] = a[1];
      s[5] = a[2];
    }
  }
  const double* R0 = d.R[0].data();
  for (int b = nbodies - 1; b > 0; --b) {
    const double* s = S[b];
    const double* I = d.cI[ix(b)].data();
    const double* h = d.ch[ix(b)].data();
    const double m = d.cm[ix(b)];
    // F = I^C s: n = I w + h × v, f = m v − h × w.
    double F[6];
    double hv[3], hw[3];
    cross(h, s + 3, hv);
    cross(h, s, hw);
    for (int i = 0; i < 3; ++i) {
      F[i] = I[i] * s[0] + I[i + 3] * s[1] + I[i + 6] * s[2] + hv[i];
      F[3 + i] = m * s[3 + i] - hw[i];
    }
    const int vi = vIndex[b];
    const double gi = gain[b];
    Mp[vi + nv * vi] +=
        gi * gi * (s[0] * F[0] + s[1] * F[1] + s[2] * F[2] + s[3] * F[3] + s[4] * F[4] + s[5] * F[5]);
    for (int c = parentOf[b]; c > 0; c = parentOf[c]) {
      const double* sc = S[c];
      const double x =
          gi * gain[c] *
          (sc[0] * F[0] + sc[1] * F[1] + sc[2] * F[2] + sc[3] * F[3] + sc[4] * F[4] + sc[5] * F[5]);
      Mp[vi + nv * vIndex[c]] += x;
      Mp[vIndex[c] + nv * vi] += x;
    }
    if (floating_base) {
      double Fr[6];
      rotateT(R0, F, Fr);
      rotateT(R0, F + 3, Fr + 3);
      for (int k = 0; k < 6; ++k) {
        Mp[k + nv * vi] += gi * Fr[k];
        Mp[vi + nv * k] += gi * Fr[k];
      }
    }
  }
  if (floating_base) {
    // The whole robot in root axes: I ← R0ᵀ I R0, h ← R0ᵀ h.
    double T[9], Ir[9];
    const double* I = d.cI[0].data();
    for (int j = 0; j < 3; ++j) rotateT(R0, I + 3 * j, T + 3 * j);  // R0ᵀ I
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        Ir[i + 3 * j] = T[i] * R0[3 * j] + T[i + 3] * R0[3 * j + 1] + T[i + 6] * R0[3 * j + 2];
    for (int k = 0; k < 9; ++k) d.cI[0].data()[k] = Ir[k];
    double hr[3];
    rotateT(R0, d.ch[0].data(), hr);
    for (int i = 0; i < 3; ++i) d.ch[0](i) = hr[i];
  }
}
