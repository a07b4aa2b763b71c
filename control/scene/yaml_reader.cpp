#include "scene/yaml_reader.hpp"

#include <cstdio>
#include <cstring>
#include <memory>

namespace mrqp::scene {

namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

void yamlError(const std::string& file, const YAML::Exception& e) {
  const int line = e.mark.is_null() ? 1 : e.mark.line + 1;
  throw SceneError(file + ":" + std::to_string(line) + ": yaml: " + e.msg);
}

YAML::Node parseYamlDocument(const std::string& text, const std::string& file_name_for_messages) {
  const Reader r(file_name_for_messages);
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(text);
  } catch (const YAML::Exception& e) {
    yamlError(file_name_for_messages, e);
  }
  if (documents.empty()) {
    return YAML::Node();
  }
  if (documents.size() > 1) {
    r.fail(documents[1], "", "expected one YAML document, found " + std::to_string(documents.size()));
  }
  return documents.front();
}

std::string readTextFile(const std::string& path) {
  const std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) {
    throw SceneError(path + ": cannot open: " + std::strerror(errno));
  }
  std::string text;
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, f.get())) > 0) {
    text.append(buffer, n);
  }
  if (std::ferror(f.get()) != 0) {
    throw SceneError(path + ": cannot open: " + std::strerror(errno));
  }
  return text;
}

}  // namespace mrqp::scene
