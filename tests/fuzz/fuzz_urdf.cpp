// libFuzzer harness: the model generator's URDF loader and validation (model_gen/src/urdf_loader:
// urdfdom, the kinematic tree, meshes resolved against tests/data/meshes) and, for a URDF that
// loads, the code emitter.
//
// Properties beyond "no crash, no undefined behaviour, no allocation beyond libFuzzer's limit, no
// hang": a rejection is a ModelError (never another exception), and generated code holds no
// control character but newline (a name can neither end a comment line nor smuggle bytes in).
#include <cstddef>
#include <cstdint>
#include <string>

#include "code_emitter.hpp"
#include "fuzz_check.hpp"
#include "urdf_loader.hpp"

namespace {

bool printableCode(const std::string& text) {
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\n') || u == 0x7F) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  mrqp::gen::LoadOptions options;
  options.floating_base = (size & 1u) != 0;
  mrqp::gen::KinematicTree tree;
  try {
    tree = mrqp::gen::loadUrdfString(xml, "fuzz.urdf", MRQP_FUZZ_MESH_DIR, options);
  } catch (const mrqp::gen::ModelError& e) {
    MRQP_FUZZ_CHECK(std::string(e.what()).size() > 0);
    return 0;
  }
  const mrqp::gen::EmittedModel model = mrqp::gen::emitModel(tree, "fuzzmodel", "fuzz.urdf", false);
  MRQP_FUZZ_CHECK(printableCode(model.header) && printableCode(model.source));
  return 0;
}
