// Whole-file reads with a size limit (bounded_file.hpp).
#include "bounded_file.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace mrqp::gen {

BoundedRead readFileAtMost(const std::string& path, std::uint64_t max_bytes, const std::string& kind) {
  namespace fs = std::filesystem;
  BoundedRead r;
  const std::string limit = "larger than the " + std::to_string(max_bytes) + "-byte " + kind + "limit";
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (path.empty() || !fs::exists(st)) {
    r.error = "file not found";
    return r;
  }
  if (!fs::is_regular_file(st)) {
    r.error = "not a regular file";
    return r;
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes) {
    r.error = limit + " (" + std::to_string(size) + " bytes)";
    r.too_large = true;
    return r;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    r.error = "cannot open file";
    return r;
  }
  // Read in chunks up to one byte past the limit: the size reported is only a hint.
  constexpr std::size_t kChunk = 1 << 16;
  char buf[kChunk];
  while (in) {
    in.read(buf, kChunk);
    const std::streamsize got = in.gcount();
    if (got <= 0) break;
    r.data.append(buf, static_cast<std::size_t>(got));
    if (r.data.size() > max_bytes) {
      r.data.clear();
      r.error = limit + " (more bytes than the size the file reported)";
      r.too_large = true;
      return r;
    }
  }
  if (in.bad()) {
    r.data.clear();
    r.error = "cannot read file";
    return r;
  }
  r.ok = true;
  return r;
}

}  // namespace mrqp::gen
