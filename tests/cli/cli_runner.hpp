#pragma once
// Runs the imunoise executable as a user would, capturing exit code, stdout and stderr.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace imunoise::test {

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

/// A scratch directory removed at destruction.
class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("imunoise-cli-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& content) const {
    std::ofstream(file(name), std::ios::binary) << content;
    return file(name);
  }

 private:
  static int& counter() {
    static int n = 0;
    return n;
  }
  std::filesystem::path path_;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// One value per line, to the last bit (%.17g): the text a user's file would hold.
inline std::string column_text(const std::vector<double>& values) {
  std::string s;
  char buf[64];
  for (double v : values) {
    std::snprintf(buf, sizeof buf, "%.17g\n", v);
    s += buf;
  }
  return s;
}

inline std::string quote(const std::string& arg) {
  std::string q = "'";
  for (char c : arg) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs `imunoise args...` with `stdin_text` on standard input.
inline CliResult run_cli(const std::vector<std::string>& args, const std::string& stdin_text = "") {
  TempDir dir;
  const std::string in = dir.write("stdin", stdin_text);
  std::string command = quote(IMUNOISE_CLI_PATH);
  for (const auto& a : args) command += " " + quote(a);
  command += " < " + quote(in) + " > " + quote(dir.file("out")) + " 2> " + quote(dir.file("err"));
  const int status = std::system(command.c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = slurp(dir.file("out"));
  result.err = slurp(dir.file("err"));
  return result;
}

}  // namespace imunoise::test
