#include <cstdio>

#include "panda.hpp"

int main() {
  static panda::Data d;
  panda::ConfigVector q;
  panda::neutral(q);
  panda::MassMatrix M;
  panda::crba(d, q, M);
  std::printf("panda nq %d nv %d M00 %.6f mass %.4f\n", panda::nq, panda::nv, M(0, 0), panda::totalMass());
  return M(0, 0) > 0.0 ? 0 : 1;
}
