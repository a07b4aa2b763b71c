// Reading a whole input file with a size limit: the size is checked before reading (a sparse 1 TB
// file is refused at once) and the read stops after the limit whatever the file claims (a device,
// a pipe or /proc file that reports no size, a file that grows). Used for URDF and mesh files.
#pragma once

#include <cstdint>
#include <string>

namespace mrqp::gen {

struct BoundedRead {
  bool ok = false;
  bool too_large = false;  ///< the error is the size limit
  std::string data;        ///< the file's bytes when ok
  std::string error;       ///< otherwise: "file not found", "not a regular file", "cannot open file",
                           ///< "cannot read file", "larger than the N-byte KIND limit (M bytes)" (too_large)
};

/// Reads the regular file at `path` if it holds at most `max_bytes` bytes; `kind` names the limit
/// in the error ("URDF " gives "larger than the N-byte URDF limit (M bytes)").
BoundedRead readFileAtMost(const std::string& path, std::uint64_t max_bytes, const std::string& kind = "");

}  // namespace mrqp::gen
