// The shared YAML reading of yaml_reader.hpp: one document parsed without yaml-cpp's LoadAll, and
// whole files read within a size limit.
#include "scene/yaml_reader.hpp"

#include <sys/stat.h>
#include <yaml-cpp/eventhandler.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>

namespace mrqp::scene {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

/// Follows the parser's events without building nodes: where each document starts (the mark of
/// its first node) and how many there are.
class DocumentCounter : public YAML::EventHandler {
 public:
  const YAML::Mark& documentStart() const { return document_start_; }
  const YAML::Mark& firstNode() const { return first_node_; }

  void OnDocumentStart(const YAML::Mark& mark) override {
    document_start_ = mark;
    first_node_ = mark;
    seen_node_ = false;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    node(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnMapEnd() override {}

 private:
  void node(const YAML::Mark& mark) {
    if (!seen_node_) first_node_ = mark;
    seen_node_ = true;
  }

  bool seen_node_ = false;
  YAML::Mark document_start_ = YAML::Mark::null_mark();
  YAML::Mark first_node_ = YAML::Mark::null_mark();
};

}  // namespace

void yamlError(const std::string& file, const YAML::Exception& e) {
  const int line = e.mark.is_null() ? 1 : e.mark.line + 1;
  throw SceneError(file + ":" + std::to_string(line) + ": yaml: " + e.msg);
}

YAML::Node parseYamlDocument(const std::string& text, const std::string& file_name_for_messages) {
  const Reader r(file_name_for_messages);
  // yaml-cpp 0.7's LoadAll calls Parser::HandleNextDocument until it returns false; after a
  // document followed by a token no document can start with (the ',' of "[],"), it returns true
  // forever without consuming anything, and LoadAll appends a null document each time until the
  // memory is gone. So the documents are first counted with events only (no nodes), and a second
  // document, or a "document" that starts where the previous one did, is an error; then the one
  // document is loaded.
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentCounter counter;
    if (!parser.HandleNextDocument(counter)) {
      return YAML::Node();
    }
    if (parser.HandleNextDocument(counter)) {
      const YAML::Mark start = counter.documentStart();
      const YAML::Mark node = counter.firstNode();
      if (parser.HandleNextDocument(counter) && counter.documentStart().pos == start.pos) {
        // no progress: a token that neither continues the document nor starts one
        const auto at = static_cast<std::size_t>(start.pos);
        throw SceneError(file_name_for_messages + ":" + std::to_string(start.line + 1) +
                         ": yaml: unexpected " +
                         (at < text.size() ? "'" + text.substr(at, 1) + "'" : std::string("content")) +
                         " after the end of the document");
      }
      r.fail(node.is_null() ? 1 : node.line + 1, "", "expected one YAML document, found more than one");
    }
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    yamlError(file_name_for_messages, e);
  }
}

std::string readTextFile(const std::string& path, std::size_t max_bytes) {
  const std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) {
    throw SceneError(path + ": cannot open: " + std::strerror(errno));
  }
  const auto tooLarge = [&] {
    return SceneError(path + ": too large: more than " + std::to_string(max_bytes) +
                      " bytes, the limit of this kind of file");
  };
  struct stat st {};
  if (fstat(fileno(f.get()), &st) == 0 && S_ISREG(st.st_mode) &&
      static_cast<unsigned long long>(st.st_size) > max_bytes) {
    throw tooLarge();
  }
  // Read at most max_bytes + 1 bytes: a device or pipe without end (/dev/zero) is refused too.
  std::string text;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, f.get())) > 0) {
    if (n > max_bytes - text.size()) {
      throw tooLarge();
    }
    text.append(buffer, n);
  }
  if (std::ferror(f.get()) != 0) {
    throw SceneError(path + ": cannot open: " + std::strerror(errno));
  }
  return text;
}

}  // namespace mrqp::scene
