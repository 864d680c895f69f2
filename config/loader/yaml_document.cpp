// Reading a YAML document (yaml_fields.h): the file, one document only, syntax errors with their
// line and column.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include <yaml-cpp/eventhandler.h>

#include "config/loader/yaml_fields.h"
#include "config/loader/yaml_text.h"

namespace sonarloop::config {

using yaml_text::mark_column;
using yaml_text::mark_line;
using yaml_text::quote;

std::string read_text_file(const std::string& path) {
  namespace fs = std::filesystem;
  const auto fail = [&](const std::string& problem) {
    throw ConfigError(ConfigIssue{path, "(file)", problem, "a readable YAML file", {}, 0, 0});
  };
  std::error_code ec;
  const auto st = fs::status(path, ec);
  if (!fs::exists(st)) fail("no such file");
  if (fs::is_directory(st)) fail("is a directory, not a file");
  if (!fs::is_regular_file(st)) fail("is not a regular file (a FIFO or a device?)");
  if (fs::file_size(path, ec) > kMaxYamlFileBytes) {
    fail("is larger than " + std::to_string(kMaxYamlFileBytes >> 20) + " MB: not a scenario file?");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(std::string("cannot be opened: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) fail("cannot be read");
  return ss.str();
}

namespace {

// Notes where each document starts; builds nothing.
class DocumentStarts : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override { marks.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}

  std::vector<YAML::Mark> marks;
};

ConfigIssue syntax_issue(const std::string& file, const std::string& problem,
                         const YAML::Mark& mark) {
  return {file,
          "",
          "YAML syntax error: " + problem,
          "well-formed YAML (see config/reference.yaml)",
          {},
          mark_line(mark),
          mark_column(mark)};
}

}  // namespace

Field parse_document(const std::string& yaml_text, const std::string& file) {
  try {
    // Count the documents first, stopping at the second. Not YAML::LoadAll: in yaml-cpp 0.7 a
    // token no document can start with (a ',' at the top level) makes LoadAll loop for ever,
    // adding empty documents until memory runs out (yaml-cpp issue #1040, fixed upstream by
    // PR #1319). Here such a token shows as a second document starting where the first did.
    std::istringstream in(yaml_text);
    YAML::Parser parser(in);
    DocumentStarts starts;
    while (starts.marks.size() < 2 && parser.HandleNextDocument(starts)) {
    }
    if (starts.marks.size() == 2) {
      const YAML::Mark& m = starts.marks[1];
      if (m.pos == starts.marks[0].pos) {
        const auto pos = static_cast<std::size_t>(std::max(m.pos, 0));
        const std::string what =
            pos < yaml_text.size() ? quote(yaml_text.substr(pos, 1)) : std::string("input");
        throw ConfigError(syntax_issue(file, "unexpected " + what, m));
      }
      throw ConfigError(ConfigIssue{file,
                                    "",
                                    "holds more than one YAML document",
                                    "a single document",
                                    {},
                                    mark_line(m),
                                    mark_column(m)});
    }
    const YAML::Node root = YAML::Load(yaml_text);
    return Field(root.IsDefined() ? root : YAML::Node(YAML::NodeType::Null), file,
                 std::make_shared<const std::string>(yaml_text));
  } catch (const YAML::Exception& e) {
    throw ConfigError(syntax_issue(file, e.msg, e.mark));
  }
}

}  // namespace sonarloop::config
