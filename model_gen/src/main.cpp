// mrqp-gen: URDF -> allocation-free C++ model code. See docs/model_gen.md. Any failure is one
// error line on stderr and a non-zero exit; exit 0 means the model's files are written.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "code_emitter.hpp"
#include "urdf_loader.hpp"

namespace {

const char* kUsage =
    "usage: mrqp-gen <file.urdf> --name NAME --out DIR [--floating-base] [--probe]\n"
    "                [--package-path DIR]... [--allow-nonphysical-inertia] [--quiet]\n"
    "Generates DIR/NAME.hpp and DIR/NAME.cpp (and DIR/NAME_probe.cpp with --probe).\n";

/// Writes `text` to `path` unless the file already holds exactly that text (keeps builds incremental).
bool writeIfChanged(const std::filesystem::path& path, const std::string& text, std::string& error) {
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      std::stringstream ss;
      ss << in.rdbuf();
      if (ss.str() == text) return true;
    }
  }
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out || !(out << text) || !out.flush()) {
      error = "cannot write " + tmp.string();
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    error = "cannot rename " + tmp.string() + " to " + path.string() + ": " + ec.message();
    return false;
  }
  return true;
}

/// `text` on one line: control characters (a newline in a file name, say) written as \xHH.
std::string oneLine(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7F) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(c));
      out += buf;
    } else {
      out += ch;
    }
  }
  return out;
}

int run(int argc, char** argv) {
  std::string urdf, name, out;
  bool probe = false, quiet = false;
  mrqp::gen::LoadOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](const char* opt) -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "mrqp-gen: " << opt << " needs a value\n" << kUsage;
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--name")
      name = value("--name");
    else if (arg == "--out")
      out = value("--out");
    else if (arg == "--floating-base")
      options.floating_base = true;
    else if (arg == "--probe")
      probe = true;
    else if (arg == "--allow-nonphysical-inertia")
      options.allow_nonphysical_inertia = true;
    else if (arg == "--quiet")
      quiet = true;
    else if (arg == "--package-path")
      options.package_paths.push_back(value("--package-path"));
    else if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "mrqp-gen: unknown option " << oneLine(arg) << "\n" << kUsage;
      return 2;
    } else if (urdf.empty())
      urdf = arg;
    else {
      std::cerr << "mrqp-gen: more than one URDF file given (" << oneLine(urdf) << ", " << oneLine(arg)
                << ")\n"
                << kUsage;
      return 2;
    }
  }
  if (urdf.empty() || name.empty() || out.empty()) {
    std::cerr << "mrqp-gen: missing "
              << (urdf.empty()   ? "URDF file"
                  : name.empty() ? "--name"
                                 : "--out")
              << "\n"
              << kUsage;
    return 2;
  }
  if (!mrqp::gen::isValidModelName(name)) {
    std::cerr << "mrqp-gen: --name '" << oneLine(name) << "' is not a valid C++ identifier\n";
    return 2;
  }
  mrqp::gen::KinematicTree tree;
  try {
    tree = mrqp::gen::loadUrdfFile(urdf, options);
  } catch (const mrqp::gen::ModelError& e) {
    std::cerr << "mrqp-gen: error: " << oneLine(e.what()) << "\n";
    return 1;
  }
  if (!quiet)
    for (const auto& w : tree.warnings)
      std::cerr << "mrqp-gen: warning: " << oneLine(urdf) << ": " << oneLine(w) << "\n";

  const std::string origin = std::filesystem::path(urdf).filename().string();
  const mrqp::gen::EmittedModel code = mrqp::gen::emitModel(tree, name, origin, probe);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) {
    std::cerr << "mrqp-gen: error: cannot create " << oneLine(out) << ": " << ec.message() << "\n";
    return 1;
  }
  std::string error;
  const std::filesystem::path dir(out);
  if (!writeIfChanged(dir / (name + ".hpp"), code.header, error) ||
      !writeIfChanged(dir / (name + ".cpp"), code.source, error) ||
      (probe && !writeIfChanged(dir / (name + "_probe.cpp"), code.probe, error))) {
    std::cerr << "mrqp-gen: error: " << oneLine(error) << "\n";
    return 1;
  }
  if (!quiet)
    std::printf("mrqp-gen: %s -> %s/%s.{hpp,cpp}: %zu bodies, %zu frames, nq %d, nv %d, mass %.6g kg%s\n",
                oneLine(urdf).c_str(), oneLine(out).c_str(), name.c_str(), tree.bodies.size(),
                tree.frames.size(), tree.nq, tree.nv, tree.totalMass(),
                tree.floating_base ? ", floating base" : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "mrqp-gen: error: " << oneLine(e.what()) << "\n";
  } catch (...) {
    std::cerr << "mrqp-gen: error: unknown exception\n";
  }
  return 1;
}
