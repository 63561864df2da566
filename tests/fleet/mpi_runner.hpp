#pragma once
// Runs the imunoise executable under mpirun (Open MPI) for the tests: oversubscribed (CI has 2
// cores) and allowed as root (CI runs as root), bounded by `timeout` so a hang fails the test.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace imunoise::test {

inline bool have_mpi() { return std::string(IMUNOISE_MPIEXEC).size() > 0; }

#define IMUNOISE_REQUIRE_MPI()                                                              \
  if (!::imunoise::test::have_mpi()) {                                                     \
    GTEST_SKIP() << "imunoise was built without MPI (IMUNOISE_MPI=OFF): mpirun tests skipped"; \
  }

/// `mpirun -np ranks imunoise args...`; the exit code is timeout's 124 on a hang.
inline CliResult run_mpi(int ranks, const std::vector<std::string>& args, int timeout_s = 120,
                         const std::string& env = "") {
  TempDir dir;
  std::string command = env + " timeout " + std::to_string(timeout_s) + " " +
                        quote(IMUNOISE_MPIEXEC) + " --oversubscribe --allow-run-as-root -np " +
                        std::to_string(ranks) + " " + quote(IMUNOISE_CLI_PATH);
  for (const auto& a : args) command += " " + quote(a);
  command += " < /dev/null > " + quote(dir.file("out")) + " 2> " + quote(dir.file("err"));
  const int status = std::system(command.c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = slurp(dir.file("out"));
  result.err = slurp(dir.file("err"));
  return result;
}

}  // namespace imunoise::test
