// COLLADA 1.4/1.5 meshes: vertex positions through <vertices>/<source>/<accessor>, node transforms
// of the visual scene, <asset><unit> (the rules and limitations: mesh_reader.hpp).
#include "mesh_format.hpp"
#include "mesh_limits.hpp"
#include "text_tokens.hpp"
#include "unit_direction.hpp"
#include "xml_document.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string_view>
#include <unordered_map>

namespace mrqp::gen::mesh {

namespace {

// ---- 4x4 transforms -------------------------------------------------------------------

// Row-major affine transforms, multiplied in a fixed order so that the vertices read do not
// depend on how the library was compiled (Eigen may vectorise products differently).
struct Mat4 {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  double& operator()(int r, int c) { return m[static_cast<std::size_t>(4 * r + c)]; }
  double operator()(int r, int c) const { return m[static_cast<std::size_t>(4 * r + c)]; }

  Mat4 operator*(const Mat4& o) const {
    Mat4 p;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) {
        p(r, c) = (*this)(r, 0) * o(0, c) + (*this)(r, 1) * o(1, c) + (*this)(r, 2) * o(2, c) +
                  (*this)(r, 3) * o(3, c);
      }
    }
    return p;
  }

  // The affine part applied to a point (a projective bottom row is ignored).
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const {
    Eigen::Vector3d y;
    for (int r = 0; r < 3; ++r) {
      y[r] = (*this)(r, 0) * x[0] + (*this)(r, 1) * x[1] + (*this)(r, 2) * x[2] + (*this)(r, 3);
    }
    return y;
  }

  static Mat4 rowMajor(const std::vector<double>& v) {
    Mat4 t;
    std::copy(v.begin(), v.begin() + 16, t.m.begin());
    return t;
  }

  // Rotation by `degrees` about (x, y, z) (need not be unit, normalised without overflow:
  // unit_direction.hpp; zero gives the identity).
  static Mat4 rotation(double x, double y, double z, double degrees) {
    Mat4 t;
    const double d = directionDivisor(x, y, z);
    if (d == 0.0) return t;
    x /= d;
    y /= d;
    z /= d;
    const double len = std::sqrt(x * x + y * y + z * z);
    x /= len;
    y /= len;
    z /= len;
    constexpr double kPi = 3.14159265358979323846;
    const double a = degrees * kPi / 180.0;
    const double c = std::cos(a);
    const double s = std::sin(a);
    const double k = 1.0 - c;
    t(0, 0) = c + x * x * k;
    t(0, 1) = x * y * k - z * s;
    t(0, 2) = x * z * k + y * s;
    t(1, 0) = y * x * k + z * s;
    t(1, 1) = c + y * y * k;
    t(1, 2) = y * z * k - x * s;
    t(2, 0) = z * x * k - y * s;
    t(2, 1) = z * y * k + x * s;
    t(2, 2) = c + z * z * k;
    return t;
  }
};

class ColladaReader {
 public:
  explicit ColladaReader(const XmlDocument& doc) : doc_(doc) {
    for (std::size_t i = 0; i < doc_.size(); ++i) {
      if (const std::string* id = doc_[i].attr("id")) ids_.emplace(*id, i);  // first wins
    }
  }

  void read(VertexSet& out) {
    const XmlElement& root = doc_[0];
    if (root.name != "COLLADA") {
      fail("malformed COLLADA: the root element is <" + root.rawName + ">, not <COLLADA>");
    }
    double meter = 1.0;
    if (const auto asset = child(0, "asset")) {
      if (const auto unit = child(*asset, "unit")) {
        if (const std::string* m = doc_[*unit].attr("meter")) {
          if (!parseDouble(*m, meter) || !std::isfinite(meter) || meter <= 0.0) {
            fail("malformed COLLADA: invalid <unit meter=" + quoteToken(*m) + ">");
          }
        }
      }
    }
    unit_ = meter;

    if (const auto scene = visualScene()) {
      for (const std::size_t c : doc_[*scene].children) {
        if (doc_[c].name == "node") visitNode(c, Mat4{}, 0, out);
      }
    }
    if (instanced_ == 0) {  // no scene, or it instantiates no mesh: every mesh as stored
      for (std::size_t i = 0; i < doc_.size(); ++i) {
        if (doc_[i].name != "geometry") continue;
        if (const auto mesh = child(i, "mesh")) addMesh(*mesh, Mat4{}, out);
      }
    }
  }

 private:
  static constexpr int kMaxNodeDepth = 256;

  std::optional<std::size_t> child(std::size_t parent, std::string_view name) const {
    for (const std::size_t c : doc_[parent].children) {
      if (doc_[c].name == name) return c;
    }
    return std::nullopt;
  }

  std::string describe(std::size_t e) const {
    std::string d = "<" + doc_[e].name;
    if (const std::string* id = doc_[e].attr("id"))
      d += " id=" + quoteToken(*id);
    else if (const std::string* nm = doc_[e].attr("name"))
      d += " name=" + quoteToken(*nm);
    return d + ">";
  }

  // The element named by a "#id" reference held in attribute `attr` of element `from`.
  std::size_t resolve(std::size_t from, const char* attr, std::string_view expected) const {
    const std::string* ref = doc_[from].attr(attr);
    if (ref == nullptr) fail("malformed COLLADA: " + describe(from) + " without a '" + attr + "' attribute");
    if (ref->empty() || (*ref)[0] != '#') {
      fail("unsupported COLLADA: external reference " + quoteToken(*ref) + " in " + describe(from));
    }
    const auto it = ids_.find(ref->substr(1));
    if (it == ids_.end())
      fail("malformed COLLADA: " + describe(from) + " refers to missing " + quoteToken(*ref));
    if (doc_[it->second].name != expected) {
      fail("malformed COLLADA: " + quoteToken(*ref) + " in " + describe(from) + " is a <" +
           doc_[it->second].name + ">, not a <" + std::string(expected) + ">");
    }
    return it->second;
  }

  // The numbers of element e's text, at most `most` of them (the rest is not parsed).
  std::vector<double> numbers(std::size_t e,
                              std::size_t most = std::numeric_limits<std::size_t>::max()) const {
    std::vector<double> v;
    const std::string_view text = doc_[e].text;
    std::size_t i = 0;
    while (i < text.size() && v.size() < most) {
      while (i < text.size() && isSpace(text[i])) ++i;
      const std::size_t b = i;
      while (i < text.size() && !isSpace(text[i])) ++i;
      if (i == b) break;
      const std::string_view tok = text.substr(b, i - b);
      double x = 0.0;
      if (!parseDouble(tok, x) || !std::isfinite(x)) {
        fail("malformed COLLADA: bad number " + quoteToken(tok) + " in " + describe(e));
      }
      v.push_back(x);
    }
    return v;
  }

  // Exactly `expected` numbers (one more is read to tell a longer list).
  std::vector<double> numbers(std::size_t e, std::size_t expected, std::size_t node) const {
    std::vector<double> v = numbers(e, expected + 1);
    if (v.size() != expected) {
      fail("malformed COLLADA: <" + doc_[e].name + "> in " + describe(node) + " has " +
           (v.size() > expected ? "more than " + std::to_string(expected) : std::to_string(v.size())) +
           " numbers, expected " + std::to_string(expected));
    }
    return v;
  }

  // The numbers of a <float_array>, parsed once however often its mesh is instanced.
  const std::vector<double>& arrayNumbers(std::size_t e) {
    auto it = arrays_.find(e);
    if (it == arrays_.end()) it = arrays_.emplace(e, numbers(e)).first;
    return it->second;
  }

  std::size_t sizeAttr(std::size_t e, const char* name, std::size_t fallback) const {
    const std::string* a = doc_[e].attr(name);
    if (a == nullptr) return fallback;
    std::uint64_t v = 0;
    if (!parseUnsigned(*a, v) || v > std::numeric_limits<std::uint32_t>::max()) {
      fail("malformed COLLADA: invalid " + std::string(name) + "=" + quoteToken(*a) + " in " + describe(e));
    }
    return static_cast<std::size_t>(v);
  }

  std::optional<std::size_t> visualScene() const {
    if (const auto scene = child(0, "scene")) {
      if (const auto ivs = child(*scene, "instance_visual_scene")) {
        return resolve(*ivs, "url", "visual_scene");
      }
    }
    if (const auto lib = child(0, "library_visual_scenes")) return child(*lib, "visual_scene");
    return std::nullopt;
  }

  Mat4 localTransform(std::size_t node) const {
    Mat4 t;
    for (const std::size_t c : doc_[node].children) {
      const std::string& n = doc_[c].name;
      Mat4 m;
      if (n == "matrix") {
        m = Mat4::rowMajor(numbers(c, 16, node));
      } else if (n == "translate") {
        const std::vector<double> v = numbers(c, 3, node);
        m(0, 3) = v[0];
        m(1, 3) = v[1];
        m(2, 3) = v[2];
      } else if (n == "rotate") {
        const std::vector<double> v = numbers(c, 4, node);
        m = Mat4::rotation(v[0], v[1], v[2], v[3]);
      } else if (n == "scale") {
        const std::vector<double> v = numbers(c, 3, node);
        m(0, 0) = v[0];
        m(1, 1) = v[1];
        m(2, 2) = v[2];
      } else if (n == "lookat" || n == "skew") {
        fail("unsupported COLLADA: <" + n + "> transform in " + describe(node));
      } else {
        continue;
      }
      t = t * m;
    }
    return t;
  }

  void visitNode(std::size_t node, const Mat4& parent, int depth, VertexSet& out) {
    if (depth > kMaxNodeDepth) {
      fail("unsupported COLLADA: nodes nested deeper than " + std::to_string(kMaxNodeDepth) +
           " (an <instance_node> cycle?) at " + describe(node));
    }
    if (++visits_ > kMaxColladaNodeVisits) {
      fail("unsupported COLLADA: more than " + std::to_string(kMaxColladaNodeVisits) +
           " node visits (the COLLADA node-visit limit; <instance_node> references multiply them) at " +
           describe(node));
    }
    sceneElements_ += doc_[node].children.size();
    if (sceneElements_ > kMaxColladaSceneElements) {
      fail("unsupported COLLADA: more than " + std::to_string(kMaxColladaSceneElements) +
           " elements examined in the visual scene (the COLLADA scene limit) at " + describe(node));
    }
    const Mat4 t = parent * localTransform(node);
    for (const std::size_t c : doc_[node].children) {
      const std::string& n = doc_[c].name;
      if (n == "node") {
        visitNode(c, t, depth + 1, out);
      } else if (n == "instance_node") {
        visitNode(resolve(c, "url", "node"), t, depth + 1, out);
      } else if (n == "instance_geometry") {
        const std::size_t geometry = resolve(c, "url", "geometry");
        if (const auto mesh = child(geometry, "mesh")) addMesh(*mesh, t, out);
      } else if (n == "instance_controller") {
        const std::size_t controller = resolve(c, "url", "controller");
        const auto skin = child(controller, "skin");
        if (!skin) continue;  // morph controllers are not read
        const std::size_t geometry = resolve(*skin, "source", "geometry");
        Mat4 bind;
        if (const auto bsm = child(*skin, "bind_shape_matrix"))
          bind = Mat4::rowMajor(numbers(*bsm, 16, *skin));
        if (const auto mesh = child(geometry, "mesh")) addMesh(*mesh, t * bind, out);
      }
    }
  }

  void addMesh(std::size_t mesh, const Mat4& t, VertexSet& out) {
    const std::size_t geometry = doc_[mesh].parent;
    const std::string where = "the <mesh> of " + describe(geometry);
    const auto vertices = child(mesh, "vertices");
    if (!vertices) fail("malformed COLLADA: " + where + " has no <vertices>");
    std::optional<std::size_t> input;
    for (const std::size_t c : doc_[*vertices].children) {
      const std::string* sem = doc_[c].attr("semantic");
      if (doc_[c].name == "input" && sem != nullptr && *sem == "POSITION") input = c;
    }
    if (!input) fail("malformed COLLADA: " + where + " has no <input semantic=\"POSITION\">");
    const std::size_t source = resolve(*input, "source", "source");
    const auto array = child(source, "float_array");
    if (!array) fail("malformed COLLADA: position " + describe(source) + " has no <float_array>");
    const std::vector<double>& values = arrayNumbers(*array);
    const std::size_t declared = sizeAttr(*array, "count", values.size());
    if (values.size() < declared) {
      fail("malformed COLLADA: " + describe(*array) + " declares " + std::to_string(declared) +
           " values but holds " + std::to_string(values.size()));
    }
    std::size_t stride = 3;
    std::size_t offset = 0;
    std::size_t count = 0;
    std::optional<std::size_t> accessor;
    if (const auto tc = child(source, "technique_common")) accessor = child(*tc, "accessor");
    if (accessor) {
      std::size_t params = 0;
      for (const std::size_t c : doc_[*accessor].children)
        if (doc_[c].name == "param") ++params;
      stride = sizeAttr(*accessor, "stride", std::max<std::size_t>(params, 3));
      offset = sizeAttr(*accessor, "offset", 0);
    }
    if (stride < 3) {
      fail("unsupported COLLADA: position accessor stride " + std::to_string(stride) + " < 3 in " + where);
    }
    const std::size_t available = declared > offset ? (declared - offset + stride - 3) / stride : 0;
    count = accessor ? sizeAttr(*accessor, "count", available) : available;
    if (count > available) {
      fail("malformed COLLADA: the position accessor of " + where + " reads " + std::to_string(count) +
           " points but " + describe(*array) + " holds " + std::to_string(declared) + " values");
    }
    for (std::size_t p = 0; p < count; ++p) {
      const std::size_t b = offset + p * stride;
      const Eigen::Vector3d x(values[b], values[b + 1], values[b + 2]);
      const Eigen::Vector3d y = unit_ * t.apply(x);
      if (!y.allFinite()) fail("malformed COLLADA: non-finite transformed vertex in " + where);
      out.add(y);
    }
    ++instanced_;
  }

  const XmlDocument& doc_;
  std::unordered_map<std::string, std::size_t> ids_;
  std::unordered_map<std::size_t, std::vector<double>> arrays_;  // <float_array> element -> numbers
  double unit_ = 1.0;
  std::size_t instanced_ = 0;
  std::size_t visits_ = 0;         // nodes visited (mesh_limits.hpp)
  std::size_t sceneElements_ = 0;  // their child elements examined
};

}  // namespace

void readDae(const std::string& data, VertexSet& out) {
  const XmlDocument doc(data, XmlLimits{kMaxXmlDepth, kMaxXmlNodes});
  ColladaReader(doc).read(out);
}

}  // namespace mrqp::gen::mesh
