// Reading the vertices of mesh files referenced by URDF <mesh filename="..."/> elements,
// and resolving the package:// / file:// URIs those elements use.
//
// Supported formats (chosen by the file extension, case-insensitive):
//   .stl  binary and ASCII STL. A file is binary when its size is exactly 84 + 50*N bytes,
//         N being the little-endian triangle count at byte 80 -- this holds even if the
//         80-byte header starts with "solid", as many exporters write. Otherwise a file
//         starting with "solid" is parsed as ASCII ("vertex x y z" lines; it must end with
//         "endsolid" and every facet must have whole vertices). Otherwise it is a
//         truncated or corrupt binary STL.
//   .obj  Wavefront OBJ: the "v x y z [w]" lines (extra components such as vertex
//         colours are ignored); faces, normals and texture coordinates are not needed.
//   .dae  COLLADA 1.4/1.5, read by a minimal XML reader (no external library). The vertex
//         positions of each <geometry><mesh> are the <float_array> of the <source> named
//         by <vertices><input semantic="POSITION" source="#..."/>, read through its
//         <accessor> (count, stride, offset) -- all of them, used by a primitive
//         (<triangles>, <polylist>, ...) or not. If the document has a visual scene (the
//         one named by <scene><instance_visual_scene>, else the first one), the meshes it
//         instantiates are transformed by their node chain (<matrix>, <translate>,
//         <rotate>, <scale>; <instance_node> and <instance_controller> with the skin's
//         bind_shape_matrix are followed) and only those meshes are returned; without a
//         scene, or if it instantiates no mesh, every mesh is returned untransformed.
//         <asset><unit meter="..."/> is applied (positions are returned in metres), as the
//         COLLADA specification and current RViz do (some older ROS tools ignored it).
//         Limitations: <up_axis> is ignored on purpose, as RViz and the ROS tools built on
//         Assimp do (a URDF mesh is used in its own frame); <lookat> and <skew> node
//         transforms are rejected with an error; <convex_mesh>, <spline>, morph
//         controllers and external document references (url="file.dae#id") are not read.
//
// Vertices are returned as distinct positions (exact duplicates, e.g. the shared corners
// of STL facets, are removed), in order of first appearance. Non-finite coordinates are
// an error. URDF <mesh scale="..."> is not applied here: multiply the vertices by it.
// Transforms use fixed-order arithmetic, so the result does not depend on the build.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

namespace mrqp::gen {

struct MeshReadResult {
  bool ok = false;
  // Empty when ok. Otherwise one line "mesh '<path>': <problem>", where <problem> is e.g.
  //   "file not found", "not a regular file", "cannot open file",
  //   "unsupported mesh format '.ply' (supported: .stl, .obj, .dae)",
  //   "truncated binary STL: ...", "binary STL size mismatch: ...",
  //   "malformed ASCII STL: ...", "truncated ASCII STL: ...",
  //   "malformed OBJ: ...", "malformed XML: ...", "malformed COLLADA: ...",
  //   "unsupported COLLADA: ...", "no vertices", and the limits of mesh_limits.hpp:
  //   "larger than the 67108864-byte mesh limit (N bytes)", "more than 5000000 vertices (the
  //   mesh vertex limit)", "<x> nested deeper than 256 levels at line L", "more than 2000000
  //   XML elements and attributes at line L", "unsupported COLLADA: more than 100000 node
  //   visits (the COLLADA node-visit limit; ...)". Text formats name the offending line
  //   ("... at line 12"); binary STL errors give the declared and actual sizes.
  std::string error;
  std::vector<Eigen::Vector3d> vertices;
};

// Reads the vertex positions of the mesh file at `path` (a plain filesystem path; use
// resolveMeshUri first for URDF filenames). Never throws for bad input; never reads more than
// kMaxMeshBytes of a file nor walks a COLLADA scene without bound (mesh_limits.hpp).
MeshReadResult readMeshVertices(const std::string& path);

// Resolves a URDF mesh filename to an existing regular file; returns "" if there is none.
//   package://pkg/rel   searched as <dir>/<pkg>/<rel> for each dir of `package_paths`,
//                       then of the ROS_PACKAGE_PATH environment variable (':'-separated);
//                       a dir whose last component is <pkg> itself is also tried as
//                       <dir>/<rel>. Last, <prefix>/share/<pkg>/<rel> for each prefix of
//                       AMENT_PREFIX_PATH (ROS 2 installs). No recursive crawling.
//   file:///abs/path    the absolute path (file://localhost/... too); %XX escapes decoded.
//   file://rel/path     (non-standard) and plain paths: relative ones are taken relative
//                       to `urdf_dir` (the current directory if it is empty).
//   other schemes       (http://, model://, ...) are not resolved.
// The returned path is lexically normalised (no "." or ".." components).
std::string resolveMeshUri(const std::string& uri, const std::string& urdf_dir,
                           const std::vector<std::string>& package_paths);

}  // namespace mrqp::gen
