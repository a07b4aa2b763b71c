// The standalone JSON probe program of a generated model (mrqp-gen --probe).
#pragma once

#include <string>

namespace mrqp::gen {

/// C++ source of NAME_probe.cpp: prints a JSON header line (nq, nv, floating_base, joint and
/// frame names), then for each stdin line "q v a" one JSON line with M, N, tau, mass, com and
/// every frame's world pose [x, y, z, qw, qx, qy, qz], numbers with 17 significant digits.
std::string emitProbe(const std::string& name, const std::string& origin);

}  // namespace mrqp::gen
