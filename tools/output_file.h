#pragma once
// A file an option names for a result written at the end of a long run (--stats-json): opened
// when the command starts, so that an unwritable place fails at once with the reason ("No such
// file or directory", "Permission denied") instead of after the whole run.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

namespace sonarloop::tools {

class OutputFile {
 public:
  // Creates or truncates `path` now. Throws std::runtime_error "OPTION PATH: cannot write: why".
  OutputFile(std::string option, std::string path);
  // Writes `text` and closes. Throws std::runtime_error naming the option, the file and why (a
  // full disk says "ENOSPC: the disk is full").
  void write_and_close(const std::string& text);

 private:
  std::string option_;
  std::string path_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
};

// A folder an option names (--out, or a file's folder), made when missing. Throws
// std::runtime_error "OPTION DIR: cannot make it: why".
void make_folder(const std::string& option, const std::filesystem::path& dir);

}  // namespace sonarloop::tools
