// The fixed (model-independent) parts of a generated model's source: scalar kernels and the
// table-driven algorithms. Written in plain scalar code on raw pointers rather than Eigen
// expressions: Eigen's product templates cost seconds of compile time per instantiation set,
// and every generated model would pay them again.
#pragma once

namespace mrqp::gen {

/// Kernels used by the per-model code (inside the generated anonymous namespace).
const char* runtimeKernels();

/// Algorithms that walk the model tables S6, vIndex, gain, parentOf, subtreeMass, bodyMass,
/// bodyFirstMoment, bodyRotationalInertia, frame_R, frame_p (anonymous namespace part).
const char* runtimeChainWalks();

/// Public functions defined on top of the above (namespace scope).
const char* runtimePublicFunctions();

}  // namespace mrqp::gen
