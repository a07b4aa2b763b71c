// Algorithms of every generated model that walk its tables (S6, vIndex, gain, parentOf,
// subtreeMass, bodyMass, bodyFirstMoment, bodyRotationalInertia, frame_R, frame_p) and its Data:
// mrqp-gen copies the text after the marker line into the anonymous namespace of each generated
// .cpp, after the model's tables and kernels.hpp. Compiled in every generated model and tested
// there against the reference implementation (tests/model_gen/test_generated_models.cpp).
#pragma once

// ---- mrqp-gen: the text below is copied into every generated model ----
/// F (a wrench in body b's frame) walked up to the root: M(v_b, v_c) = g_b g_c S_cᵀ F for every
/// ancestor c with a joint; the free-flyer root takes the whole 6-vector.
inline void chainToRoot(const Data& d, int b, const double* F0, MassMatrix& M) noexcept {
  double* Mp = M.data();
  const int vi = vIndex[b];
  const double gi = gain[b];
  double F[6] = {F0[0], F0[1], F0[2], F0[3], F0[4], F0[5]};
  for (int c = b;;) {
    const int p = parentOf[c];
    if (p < 0 || (p == 0 && !floating_base)) break;
    double G[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    forceToParent(d.Rl[ix(c)].data(), d.pl[ix(c)].data(), F, G);
    for (int k = 0; k < 6; ++k) F[k] = G[k];
    c = p;
    if (c == 0) {
      for (int k = 0; k < 6; ++k) {
        Mp[k + nv * vi] += gi * F[k];
        Mp[vi + nv * k] += gi * F[k];
      }
      break;
    }
    double x = 0.0;
    for (int k = 0; k < 6; ++k) x += S6[c][k] * F[k];
    x *= gi * gain[c];
    Mp[vi + nv * vIndex[c]] += x;
    Mp[vIndex[c] + nv * vi] += x;
  }
}

/// Composite inertia of body b added to its parent p:
/// I_p += E I Eᵀ − (Eh rᵀ + r Ehᵀ) + 2 (r·Eh) 1 − m (r rᵀ − |r|² 1), h_p += Eh + m r, m_p += m.
inline void addCompositeToParent(Data& d, int b, int p) noexcept {
  const double* E = d.Rl[ix(b)].data();
  const double* r = d.pl[ix(b)].data();
  const double* I = d.cI[ix(b)].data();
  double* Ip = d.cI[ix(p)].data();
  const double m = d.cm[ix(b)];
  double Eh[3];
  rotate(E, d.ch[ix(b)].data(), Eh);
  double EI[9];  // E I, column-major
  for (int j = 0; j < 3; ++j) rotate(E, I + 3 * j, EI + 3 * j);
  const double rEh = r[0] * Eh[0] + r[1] * Eh[1] + r[2] * Eh[2];
  const double rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      double x = EI[i] * E[j] + EI[i + 3] * E[j + 3] + EI[i + 6] * E[j + 6];  // (E I Eᵀ)(i, j)
      x -= Eh[i] * r[j] + r[i] * Eh[j] + m * r[i] * r[j];
      if (i == j) x += 2.0 * rEh + m * rr;
      Ip[i + 3 * j] += x;
    }
  double* hp = d.ch[ix(p)].data();
  for (int i = 0; i < 3; ++i) hp[i] += Eh[i] + m * r[i];
  d.cm[ix(p)] += m;
}

/// World-aligned Jacobian columns of the world point pt carried by body b (added to J).
inline void bodyJacobian(const Data& d, int b, const double* pt, Jacobian& J) noexcept {
  double* Jp = J.data();
  for (int c = b; c > 0; c = parentOf[c]) {
    double w[3], u[3], dp[3], wxd[3];
    rotate(d.R[ix(c)].data(), S6[c], w);
    rotate(d.R[ix(c)].data(), S6[c] + 3, u);
    for (int i = 0; i < 3; ++i) dp[i] = pt[i] - d.p[ix(c)][i];
    cross(w, dp, wxd);
    double* col = Jp + 6 * vIndex[c];
    const double g = gain[c];
    for (int i = 0; i < 3; ++i) {
      col[i] += g * w[i];
      col[3 + i] += g * (u[i] + wxd[i]);
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
