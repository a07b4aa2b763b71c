#include "mesh_reader.hpp"

#include "bounded_file.hpp"
#include "mesh_format.hpp"
#include "mesh_limits.hpp"
#include "text_tokens.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <string_view>
#include <system_error>
#include <utility>

namespace mrqp::gen {
namespace {

namespace fs = std::filesystem;
using mesh::MeshError;
using mesh::startsWith;
using mesh::VertexSet;

// ---- URI helpers ----------------------------------------------------------------------

bool isRegularFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::vector<std::string> envPathList(const char* name) {
  std::vector<std::string> dirs;
  const char* v = std::getenv(name);
  if (v == nullptr) return dirs;
  const std::string_view s(v);
  std::size_t b = 0;
  while (b <= s.size()) {
    std::size_t e = s.find(':', b);
    if (e == std::string_view::npos) e = s.size();
    if (e > b) dirs.emplace_back(s.substr(b, e - b));
    b = e + 1;
  }
  return dirs;
}

std::string percentDecode(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    unsigned value = 0;
    if (s[i] == '%' && i + 2 < s.size()) {
      const auto res = std::from_chars(s.data() + i + 1, s.data() + i + 3, value, 16);
      if (res.ec == std::errc() && res.ptr == s.data() + i + 3) {
        out += static_cast<char>(value);
        i += 2;
        continue;
      }
    }
    out += s[i];
  }
  return out;
}

fs::path normalised(const fs::path& p) { return p.lexically_normal(); }

}  // namespace

MeshReadResult readMeshVertices(const std::string& path) {
  MeshReadResult result;
  auto failed = [&](const std::string& problem) {
    result.ok = false;
    result.error = "mesh '" + path + "': " + problem;
    result.vertices.clear();
    return result;
  };
  try {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (path.empty() || !fs::exists(st)) return failed("file not found");
    if (!fs::is_regular_file(st)) return failed("not a regular file");

    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), mesh::lower);
    if (ext != ".stl" && ext != ".obj" && ext != ".dae") {
      return failed(ext.empty() ? "unsupported mesh format (no file extension; supported: .stl, .obj, .dae)"
                                : "unsupported mesh format '" + ext + "' (supported: .stl, .obj, .dae)");
    }

    const BoundedRead file = readFileAtMost(path, kMaxMeshBytes, "mesh ");
    if (!file.ok) return failed(file.error);
    const std::string& data = file.data;

    VertexSet vertices;
    if (ext == ".stl")
      mesh::readStl(data, vertices);
    else if (ext == ".obj")
      mesh::readObj(data, vertices);
    else
      mesh::readDae(data, vertices);
    if (vertices.empty()) return failed("no vertices");
    result.ok = true;
    result.vertices = vertices.take();
    return result;
  } catch (const MeshError& e) {
    return failed(e.problem);
  } catch (const std::bad_alloc&) {
    return failed("out of memory");
  } catch (const std::exception& e) {
    return failed(std::string("cannot read file (") + e.what() + ")");
  }
}

std::string resolveMeshUri(const std::string& uri, const std::string& urdf_dir,
                           const std::vector<std::string>& package_paths) {
  constexpr std::string_view kPackage = "package://";
  constexpr std::string_view kFile = "file://";
  if (uri.empty()) return {};

  if (startsWith(uri, kPackage)) {
    const std::string rest = uri.substr(kPackage.size());
    const std::size_t slash = rest.find('/');
    if (slash == std::string::npos || slash == 0) return {};
    const std::string pkg = rest.substr(0, slash);
    const std::size_t relBegin = rest.find_first_not_of('/', slash);
    if (relBegin == std::string::npos) return {};
    const std::string rel = rest.substr(relBegin);
    std::vector<std::string> dirs = package_paths;
    for (std::string& d : envPathList("ROS_PACKAGE_PATH")) dirs.push_back(std::move(d));
    for (const std::string& d : dirs) {
      if (d.empty()) continue;
      fs::path base = fs::path(d).lexically_normal();
      if (const fs::path c = normalised(base / pkg / rel); isRegularFile(c)) return c.string();
      if (base.filename().empty()) base = base.parent_path();  // "dir/" -> "dir"
      if (base.filename() == pkg) {
        if (const fs::path c = normalised(base / rel); isRegularFile(c)) return c.string();
      }
    }
    for (const std::string& prefix : envPathList("AMENT_PREFIX_PATH")) {
      if (const fs::path c = normalised(fs::path(prefix) / "share" / pkg / rel); isRegularFile(c)) {
        return c.string();
      }
    }
    return {};
  }

  std::string local;
  if (startsWith(uri, kFile)) {
    std::string_view rest = std::string_view(uri).substr(kFile.size());
    if (startsWith(rest, "localhost/")) rest.remove_prefix(std::string_view("localhost").size());
    local = percentDecode(rest);
  } else {
    const std::size_t colon = uri.find("://");
    if (colon != std::string::npos && colon > 0 &&
        std::all_of(uri.begin(), uri.begin() + static_cast<std::ptrdiff_t>(colon), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '+' || c == '-' || c == '.';
        })) {
      return {};  // another scheme (http://, model://, ...)
    }
    local = uri;
  }
  if (local.empty()) return {};
  fs::path p(local);
  if (p.is_relative() && !urdf_dir.empty()) p = fs::path(urdf_dir) / p;
  p = p.lexically_normal();  // "urdf/../meshes/x.stl" need not have an existing "urdf"
  return isRegularFile(p) ? p.string() : std::string();
}

}  // namespace mrqp::gen
