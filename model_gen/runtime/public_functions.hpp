// The public functions of every generated model defined on top of kernels.hpp and chain_walks.hpp
// (frame lookup, kinematics, Jacobians, bias accelerations, RNEA, centre of mass and its Jacobian,
// regressor, inertial parameters, neutral configuration): mrqp-gen copies the text after the
// marker line into the model's namespace of each generated .cpp. Compiled in every generated
// model and tested there against the reference implementation
// (tests/model_gen/test_generated_models.cpp).
#pragma once

// ---- mrqp-gen: the text below is copied into every generated model ----
int frameIndex(const char* name) noexcept {
  for (int i = 0; i < nframes; ++i)
    if (std::strcmp(frame_names[ix(i)], name) == 0) return i;
  return -1;
}

void forwardKinematics(Data& d, const ConfigVector& q) noexcept {
  localTransforms(d, q);
  worldPoses(d);
}

void forwardKinematics(Data& d, const ConfigVector& q, const TangentVector& v) noexcept {
  localTransforms(d, q);
  worldPoses(d);
  forwardPass(d, v, nullptr, false, false, d.abias);
}

Pose framePose(const Data& d, int frame) noexcept {
  const int b = frame_body[ix(frame)];
  const double* Rf = frame_R[frame];
  const double* Rb = d.R[ix(b)].data();
  Pose out;
  double* R = out.R.data();
  for (int j = 0; j < 3; ++j) {
    const double col[3] = {Rf[j], Rf[3 + j], Rf[6 + j]};
    rotate(Rb, col, R + 3 * j);
  }
  rotate(Rb, frame_p[frame], out.p.data());
  for (int i = 0; i < 3; ++i) out.p(i) += d.p[ix(b)](i);
  return out;
}

void frameJacobian(const Data& d, int frame, const Eigen::Vector3d& point, ReferenceFrame rf,
                   Jacobian& J) noexcept {
  const int b = frame_body[ix(frame)];
  double r[3], pt[3];
  pointOnBody(frame, point.data(), r);
  rotate(d.R[ix(b)].data(), r, pt);
  for (int i = 0; i < 3; ++i) pt[i] += d.p[ix(b)](i);
  bodyJacobian(d, b, pt, J);  // writes all of J
  if (rf == ReferenceFrame::Local) {
    double* Jp = J.data();
    for (int c = 0; c < nv; ++c) {
      double x[3];
      for (int h = 0; h < 2; ++h) {
        double* seg = Jp + 6 * c + 3 * h;
        rotateT(d.R[ix(b)].data(), seg, x);  // world -> body
        bodyToFrame(frame, x, seg);          // body -> frame
      }
    }
  }
}

Motion frameBiasAcceleration(const Data& d, int frame, const Eigen::Vector3d& point,
                             ReferenceFrame rf) noexcept {
  const int b = frame_body[ix(frame)];
  double r[3];
  pointOnBody(frame, point.data(), r);
  const double* w = d.v[ix(b)].data();
  const double* vl = w + 3;
  const double* dw = d.abias[ix(b)].data();
  const double* dl = dw + 3;
  double spatial[3], t[3];
  cross(dw, r, t);
  for (int i = 0; i < 3; ++i) spatial[i] = dl[i] + t[i];  // spatial acceleration at the point
  Motion out;
  if (rf == ReferenceFrame::Local) {
    bodyToFrame(frame, dw, out.data());
    bodyToFrame(frame, spatial, out.data() + 3);
  } else {
    double vp[3], wr[3], wvp[3], classical[3];
    cross(w, r, wr);
    for (int i = 0; i < 3; ++i) vp[i] = vl[i] + wr[i];
    cross(w, vp, wvp);
    for (int i = 0; i < 3; ++i) classical[i] = spatial[i] + wvp[i];
    rotate(d.R[ix(b)].data(), dw, out.data());
    rotate(d.R[ix(b)].data(), classical, out.data() + 3);
  }
  return out;
}

void rnea(Data& d, const ConfigVector& q, const TangentVector& v, const TangentVector& a,
          TangentVector& tau) noexcept {
  localTransforms(d, q);
  forwardPass(d, v, &a, true, true, d.a);
  backwardTorques(d, tau);
}

void nonLinearEffects(Data& d, const ConfigVector& q, const TangentVector& v, TangentVector& N) noexcept {
  localTransforms(d, q);
  forwardPass(d, v, nullptr, true, true, d.a);
  backwardTorques(d, N);
}

Eigen::Vector3d centerOfMass(const Data& d) noexcept {
  double s[3] = {0.0, 0.0, 0.0};
  for (int b = 0; b < nbodies; ++b) {
    double Rh[3];
    rotate(d.R[ix(b)].data(), bodyFirstMoment[b], Rh);
    for (int i = 0; i < 3; ++i) s[i] += bodyMass[b] * d.p[ix(b)](i) + Rh[i];
  }
  const double inv = totalMass() > 0.0 ? 1.0 / totalMass() : 0.0;
  return Eigen::Vector3d(s[0] * inv, s[1] * inv, s[2] * inv);
}

void comJacobian(Data& d, ComJacobian& Jc) noexcept {
  // d.ch[b] <- Σ m_i c_i (world) over the subtree of b; joint b's column is
  // g_b (w × (s_b − m_sub p_b) + m_sub u) / M with (w; u) = R_b S_b.
  const double inv = totalMass() > 0.0 ? 1.0 / totalMass() : 0.0;
  for (int b = 0; b < nbodies; ++b) {
    double Rh[3];
    rotate(d.R[ix(b)].data(), bodyFirstMoment[b], Rh);
    for (int i = 0; i < 3; ++i) d.ch[ix(b)](i) = bodyMass[b] * d.p[ix(b)](i) + Rh[i];
  }
  for (int b = nbodies - 1; b > 0; --b) d.ch[ix(parentOf[b])] += d.ch[ix(b)];
  Jc.setZero();
  double* Jp = Jc.data();
  for (int b = 1; b < nbodies; ++b) {
    double w[3], u[3], rel[3], wr[3];
    rotate(d.R[ix(b)].data(), S6[b], w);
    rotate(d.R[ix(b)].data(), S6[b] + 3, u);
    for (int i = 0; i < 3; ++i) rel[i] = d.ch[ix(b)](i) - subtreeMass[b] * d.p[ix(b)](i);
    cross(w, rel, wr);
    double* col = Jp + 3 * vIndex[b];
    for (int i = 0; i < 3; ++i) col[i] += gain[b] * inv * (wr[i] + subtreeMass[b] * u[i]);
  }
  if (floating_base) {
    const double* R0 = d.R[0].data();
    double rel[3];
    for (int i = 0; i < 3; ++i) rel[i] = d.ch[0](i) * inv - d.p[0](i);
    for (int k = 0; k < 3; ++k) {
      double lin[3];
      cross(R0 + 3 * k, rel, lin);
      for (int i = 0; i < 3; ++i) {
        Jp[3 * k + i] = lin[i];
        Jp[3 * (3 + k) + i] = R0[3 * k + i];
      }
    }
  }
}

void regressor(Data& d, const ConfigVector& q, const TangentVector& v, const TangentVector& a,
               Regressor& Y) noexcept {
  localTransforms(d, q);
  forwardPass(d, v, &a, true, false, d.a);
  Y.setZero();
  double* Yp = Y.data();
  double A[6][10];
  for (int b = floating_base ? 0 : 1; b < nbodies; ++b) {
    bodyRegressor(d.v[ix(b)].data(), d.a[ix(b)].data(), A);
    for (int c = b;;) {
      if (c == 0) {
        for (int i = 0; i < 6; ++i)
          for (int k = 0; k < 10; ++k) Yp[i + nv * (10 * b + k)] += A[i][k];
        break;
      }
      for (int k = 0; k < 10; ++k) {
        double x = 0.0;
        for (int i = 0; i < 6; ++i) x += S6[c][i] * A[i][k];
        Yp[vIndex[c] + nv * (10 * b + k)] += gain[c] * x;
      }
      const int p = parentOf[c];
      if (p == 0 && !floating_base) break;
      for (int k = 0; k < 10; ++k) {
        const double f[6] = {A[0][k], A[1][k], A[2][k], A[3][k], A[4][k], A[5][k]};
        double g[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
        forceToParent(d.Rl[ix(c)].data(), d.pl[ix(c)].data(), f, g);
        for (int i = 0; i < 6; ++i) A[i][k] = g[i];
      }
      c = p;
    }
  }
}

void inertialParameters(ParamVector& phi) noexcept {
  double* x = phi.data();
  for (int b = 0; b < nbodies; ++b) {
    const double* I = bodyRotationalInertia[b];  // column-major, symmetric
    const double vals[10] = {bodyMass[b],
                             bodyFirstMoment[b][0],
                             bodyFirstMoment[b][1],
                             bodyFirstMoment[b][2],
                             I[0],
                             I[3],
                             I[4],
                             I[6],
                             I[7],
                             I[8]};
    for (int k = 0; k < 10; ++k) x[10 * b + k] = vals[k];
  }
}

void neutral(ConfigVector& q) noexcept {
  q.setZero();
  if (floating_base) q(3) = 1.0;
}
