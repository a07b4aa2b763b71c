// Where a model's URDF file is: the runtime's models in control/model/urdf, the test and benchmark
// models in tests/data/models. One lookup for the tests and the host tools that read a URDF.
#pragma once

#include <string>
#include <vector>

namespace mrqp::testing {

/// Path of the URDF file `file` (e.g. "panda.urdf"): control/model/urdf when it is there, else
/// tests/data/models.
std::string modelUrdf(const std::string& file);

/// The file names of every model URDF of both folders, sorted.
std::vector<std::string> modelUrdfNames();

}  // namespace mrqp::testing
