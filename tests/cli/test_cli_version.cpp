// `imunoise --version` is answered before the command line parser is built (a start-up fast
// path, apps/imunoise/main.cpp); the parser's own --version, reached when more words follow,
// must say the same.
#include <gtest/gtest.h>

#include "cli/cli_runner.hpp"

namespace imunoise {
namespace {

TEST(CliVersion, FastPathAndParserAgree) {
  const auto alone = test::run_cli({"--version"});
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  EXPECT_EQ(alone.out, "imunoise 0.1.0\n");
  EXPECT_TRUE(alone.err.empty()) << alone.err;
  // Two words: CLI11 parses the line and answers from its version flag.
  const auto parsed = test::run_cli({"--version", "dev"});
  ASSERT_EQ(parsed.exit_code, 0) << parsed.err;
  EXPECT_EQ(parsed.out, alone.out);
}

}  // namespace
}  // namespace imunoise
