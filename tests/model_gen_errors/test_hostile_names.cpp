// Hostile names in a URDF: the name rule (model_gen/src/name_rule.hpp) rejects what cannot be shown
// safely, with a one-line error naming the element; what it accepts reaches the generated code only
// escaped (model_gen/src/cpp_text.hpp). Checked against the host C++ compiler (the literal's bytes as
// the compiler reads them; comments that compile under -Wall -Werror and inject nothing) and against a
// small independent lexer (the generated code of a hostile robot, comments and literals removed, is
// the code of the same robot with plain names).
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "code_emitter.hpp"
#include "cpp_text.hpp"
#include "generator_limits.hpp"
#include "name_rule.hpp"
#include "temp_dir.hpp"
#include "urdf_loader.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using mrqp::gen::cppCommentText;
using mrqp::gen::cppStringLiteral;
using mrqp::gen::LoadOptions;
using mrqp::gen::ModelError;

namespace {

const std::string kBad = std::string(MRQP_TEST_DATA_DIR) + "/bad_urdf/";
const std::string kInjected = "/tmp/mrqp-gen-injected";

std::string loadError(const std::string& xml) {
  try {
    mrqp::gen::loadUrdfString(xml, "inline.urdf", ".", LoadOptions{});
  } catch (const ModelError& e) {
    return e.what();
  }
  return "(accepted)";
}

std::string fileError(const std::string& name) {
  try {
    mrqp::gen::loadUrdfFile(kBad + name, LoadOptions{});
  } catch (const ModelError& e) {
    return e.what();
  }
  return "(accepted)";
}

/// A two-link robot with the given names (already XML-escaped).
std::string robot(const std::string& robot_name, const std::string& link_name,
                  const std::string& joint_name) {
  return "<robot name=\"" + robot_name + "\"><link name=\"base\"/><link name=\"" + link_name +
         "\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" "
         "izz=\"0.1\"/></inertial></link><joint name=\"" +
         joint_name + "\" type=\"continuous\"><parent link=\"base\"/><child link=\"" + link_name +
         "\"/><axis xyz=\"0 0 1\"/></joint></robot>";
}

bool oneLine(const std::string& s) {
  return s.find('\n') == std::string::npos && s.find('\r') == std::string::npos;
}

bool printableAscii(const std::string& s) {
  for (const char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7E) return false;
  return true;
}

using mrqp::testing::TempDir;

void writeText(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  REQUIRE(out.good());
}

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Compiles `source` with the host compiler (warnings as errors) and runs it; returns its stdout.
std::string compileAndRun(const TempDir& dir, const std::string& source) {
  writeText(dir.file("t.cpp"), source);
  const std::string compile = std::string(MRQP_TEST_CXX) +
                              " -std=c++17 -Wall -Wextra -Wpedantic -Werror -o " + dir.file("t") + " " +
                              dir.file("t.cpp") + " 2> " + dir.file("compile.log");
  const int rc = std::system(compile.c_str());
  INFO(readText(dir.file("compile.log")));
  REQUIRE(rc == 0);
  REQUIRE(std::system((dir.file("t") + " > " + dir.file("out.txt")).c_str()) == 0);
  return readText(dir.file("out.txt"));
}

/// C++ text with comments and the contents of string and character literals removed (each literal
/// becomes "" or ''), after the line splices of translation phase 2: what the compiler sees as code.
std::string codeOnly(const std::string& text) {
  std::string s;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\') {  // backslash, optional blanks, newline: a splice (as GCC reads it)
      std::size_t k = i + 1;
      while (k < text.size() && (text[k] == ' ' || text[k] == '\t')) ++k;
      if (k < text.size() && text[k] == '\n') {
        i = k;
        continue;
      }
    }
    s += text[i];
  }
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    if (s.compare(i, 2, "//") == 0) {
      while (i < s.size() && s[i] != '\n') ++i;
    } else if (s.compare(i, 2, "/*") == 0) {
      const std::size_t e = s.find("*/", i + 2);
      i = e == std::string::npos ? s.size() : e + 2;
      out += ' ';
    } else if (s.compare(i, 3, "R\"(") == 0) {
      const std::size_t e = s.find(")\"", i + 3);
      i = e == std::string::npos ? s.size() : e + 2;
      out += "R\"()\"";
    } else if (s[i] == '"' || s[i] == '\'') {
      const char q = s[i++];
      while (i < s.size() && s[i] != q && s[i] != '\n') i += s[i] == '\\' ? std::size_t{2} : std::size_t{1};
      ++i;
      out += q;
      out += q;
    } else {
      out += s[i++];
    }
  }
  return out;
}

}  // namespace

TEST_CASE("hostile names: the three generator-injection files are rejected, one line each",
          "[model_gen][hostile]") {
  const std::string robotName = fileError("injected_robot_name.urdf");
  CHECK_THAT(robotName, Contains("injected_robot_name.urdf: robot name 'arm\\x0astatic int injected") &&
                            Contains("contains the control character 0x0a at byte 4"));
  const std::string mimic = fileError("injected_mimic_name.urdf");
  CHECK_THAT(mimic, Contains("injected_mimic_name.urdf: joint 'j1\\x0a") &&
                        Contains("contains the control character 0x0a at byte 3"));
  const std::string link = fileError("newline_link_name.urdf");
  CHECK_THAT(link, Contains("newline_link_name.urdf: link 'upper\\x0aarm'") &&
                       Contains("contains the control character 0x0a at byte 6"));
  for (const auto* m : {&robotName, &mimic, &link}) {
    CHECK(oneLine(*m));
    CHECK(printableAscii(*m));
  }
  CHECK_FALSE(fs::exists(kInjected));
}

TEST_CASE("hostile names: control characters, DEL, non-ASCII bytes and over-long names are rejected",
          "[model_gen][hostile]") {
  CHECK_THAT(loadError(robot("r", "a&#9;b", "j")),
             Contains("link 'a\\x09b'") && Contains("control character 0x09"));
  CHECK_THAT(loadError(robot("r", "l", "j&#1;")),
             Contains("joint 'j\\x01'") && Contains("control character 0x01"));
  CHECK_THAT(loadError(robot("r&#127;", "l", "j")),
             Contains("robot name 'r\\x7f'") && Contains("0x7f at byte 2"));
  CHECK_THAT(loadError(robot("r", "caf\xc3\xa9", "j")),
             Contains("link 'caf\\xc3\\xa9'") && Contains("non-ASCII byte 0xc3 at byte 4"));
  CHECK_THAT(loadError(robot("r", "l", "j&#13;")), Contains("control character 0x0d"));
  // a raw control byte is not XML at all: refused before urdfdom, with its line
  CHECK_THAT(loadError("<robot name='r'>\n<link name='a\x01'/></robot>"),
             Contains("inline.urdf: control character 0x01 (not allowed in XML) at line 2"));

  const std::size_t n = mrqp::gen::kMaxNameLength;
  const std::string longest(n, 'x'), tooLong(n + 1, 'x');
  CHECK(loadError(robot("r", longest, "j")) == "(accepted)");
  CHECK_THAT(loadError(robot("r", tooLong, "j")),
             Contains("is " + std::to_string(n + 1) + " bytes long") && Contains("link 'xxxx"));
  CHECK_THAT(loadError(robot(tooLong, "l", "j")), Contains("robot name") && Contains("bytes long"));
  // an error message shows at most 80 bytes of a name
  CHECK(loadError(robot("r", tooLong, "j")).size() < 300);
}

TEST_CASE("hostile names: a mimic reference to an unknown, hostile name is reported on one line",
          "[model_gen][hostile]") {
  const std::string xml =
      "<robot name='r'><link name='a'/><link name='b'/><link name='c'/>"
      "<joint name='j1' type='continuous'><parent link='a'/><child link='b'/></joint>"
      "<joint name='j2' type='continuous'><parent link='b'/><child link='c'/>"
      "<mimic joint='x&#10;std::system(&quot;id&quot;);'/></joint></robot>";
  const std::string e = loadError(xml);
  CHECK_THAT(e, Contains("joint 'j2'") && Contains("x\\x0astd::system"));
  CHECK(oneLine(e));
}

TEST_CASE("cppStringLiteral: every byte value reads back exactly, as the compiler reads it",
          "[model_gen][hostile]") {
  std::string all;
  for (int c = 0; c < 256; ++c) all += static_cast<char>(c);
  // followed by digits and '?' sequences that an escape or a trigraph could swallow
  static const char kTricky[] =
      "\0"
      "7\1"
      "77\x7f"
      "9?\?/?\?=?\"\\";
  const std::string tricky(kTricky, sizeof kTricky - 1);
  const std::string text = all + tricky + all;
  const std::string lit = cppStringLiteral(text);
  CHECK(printableAscii(lit));
  TempDir dir;
  const std::string out = compileAndRun(
      dir, "#include <cstdio>\nstatic const char s[] = " + lit +
               ";\nint main() {\n  for (unsigned i = 0; i + 1 < sizeof s; ++i) std::printf(\"%02x\", "
               "static_cast<unsigned>(static_cast<unsigned char>(s[i])));\n  return 0;\n}\n");
  std::string expected;
  for (const char c : text) {
    char hex[4];
    std::snprintf(hex, sizeof hex, "%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
    expected += hex;
  }
  CHECK(out == expected);
}

TEST_CASE("cppCommentText: hostile text stays inside // and /* */ comments", "[model_gen][hostile]") {
  const std::vector<std::string> hostile = {
      "x\nstatic int injected = (std::system(\"touch " + kInjected + "\"), 0);\n//",
      "x */ static int injected = (std::system(\"touch " + kInjected + "\"), 0); /*",
      "ends with a backslash \\",
      "backslash and blanks \\  \t",
      "?\?/",
      "/* nested",
      "*/*/*",
      "\r\x0b\x0c\x1b[2J\x7f\xc3\xa9\xe2\x80\xae",
      std::string("nul\0byte", 8),
  };
  std::string source = "#include <cstdio>\n#include <cstdlib>\n";
  for (const auto& h : hostile) {
    const std::string c = cppCommentText(h);
    CHECK(printableAscii(c));
    CHECK(c.find("*/") == std::string::npos);
    CHECK(c.find("/*") == std::string::npos);
    CHECK(c.find("??") == std::string::npos);
    CHECK((c.empty() || c.back() != '\\'));
    source += "// " + c + "\n/* " + c + " */\n";
  }
  source += "int main() { std::printf(\"ok\"); return 0; }\n";
  // as a compiler reads it (splices first), each comment is gone whole: nothing but the program is code
  std::string plain = "#include <cstdio>\n#include <cstdlib>\n";
  for (std::size_t i = 0; i < hostile.size(); ++i) plain += "\n \n";
  CHECK(codeOnly(source) == plain + "int main() { std::printf(\"\"); return 0; }\n");
  TempDir dir;
  CHECK(compileAndRun(dir, source) == "ok");
  CHECK_FALSE(fs::exists(kInjected));
}

TEST_CASE(
    "hostile names: the generated code of a hostile robot is the plain robot's code but for comments "
    "and literals",
    "[model_gen][hostile]") {
  const auto hostile = mrqp::gen::loadUrdfFile(kBad + "hostile_names_accepted.urdf", LoadOptions{});
  const auto benign = mrqp::gen::loadUrdfFile(kBad + "hostile_names_benign.urdf", LoadOptions{});
  REQUIRE(hostile.bodies.size() == benign.bodies.size());
  CHECK(hostile.robot_name.find("*/") != std::string::npos);
  const auto h = mrqp::gen::emitModel(hostile, "m", "hostile */ file\\ ?\?/.urdf", true);
  const auto b = mrqp::gen::emitModel(benign, "m", "benign.urdf", true);
  CHECK(codeOnly(h.header) == codeOnly(b.header));
  CHECK(codeOnly(h.source) == codeOnly(b.source));
  CHECK(codeOnly(h.probe) == codeOnly(b.probe));
  // and the names are there, each as one escaped literal
  CHECK_THAT(h.source, Contains(cppStringLiteral(hostile.frames[1].name)));
  CHECK_THAT(h.header, Contains("// Model '" + cppCommentText(hostile.robot_name) + "'"));
}
