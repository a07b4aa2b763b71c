// The fixed (model-independent) parts of a generated model's source: scalar kernels and the
// table-driven algorithms. The code is real C++ in model_gen/runtime/ (kernels.hpp,
// chain_walks.hpp, public_functions.hpp), embedded into the generator at build time
// (runtime/embed.cmake): the functions below return the text after each file's marker line.
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
