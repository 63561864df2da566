#pragma once
// Runs the imunoise executable as a user would, capturing exit code, stdout and stderr.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <regex>
#include <vector>

#include <gtest/gtest.h>

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

/// Scratch paths differ between runs (process id, counter): one name for all of them.
inline std::string without_scratch_paths(const std::string& text) {
  static const std::regex scratch("imunoise-cli-[0-9]+-[0-9]+");
  return std::regex_replace(text, scratch, "imunoise-cli-X");
}

/// With IMUNOISE_CLI_SNAPSHOT_DIR set, every run's arguments, exit code, standard output and the
/// JSON documents it wrote (-o FILE.json, -o DIR/report.json) are saved there, one file per run
/// named by test and call: two builds' snapshots diffed show whether a refactoring changed what
/// a user sees (scripts/compare_snapshots.sh).
inline void snapshot(const std::vector<std::string>& args, const CliResult& result) {
  const char* root = std::getenv("IMUNOISE_CLI_SNAPSHOT_DIR");
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  if (root == nullptr || info == nullptr) return;
  static std::string last_test;
  static int call = 0;
  const std::string test = std::string(info->test_suite_name()) + "." + info->name();
  call = test == last_test ? call + 1 : 0;
  last_test = test;
  std::string text = "exit " + std::to_string(result.exit_code) + "\nargs";
  for (const auto& a : args) text += " " + a;
  text += "\n--- stdout\n" + result.out;
  for (std::size_t i = 0; i + 1 < args.size(); ++i) {
    if (args[i] != "-o" && args[i] != "--output") continue;
    std::filesystem::path out = args[i + 1];
    if (std::filesystem::is_directory(out)) out /= "report.json";
    if (out.extension() == ".json" && std::filesystem::is_regular_file(out)) {
      text += "\n--- " + out.filename().string() + "\n" + slurp(out.string());
    }
  }
  std::filesystem::create_directories(root);
  std::ofstream(std::filesystem::path(root) / (test + "." + std::to_string(call) + ".txt"))
      << without_scratch_paths(text);
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
  snapshot(args, result);
  return result;
}

}  // namespace imunoise::test
