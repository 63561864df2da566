// The README's list of subcommands (between the `subcommands:begin` and `subcommands:end`
// markers, one "- `name`: ..." line each) must name exactly the subcommands `imunoise --help`
// lists: a subcommand added, renamed or removed without the README fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace imunoise {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> sorted(std::vector<std::string> names) {
  std::sort(names.begin(), names.end());
  return names;
}

/// Names under CLI11's "Subcommands:" heading: a line indented by two spaces starts an entry
/// (wrapped descriptions are indented further); the section ends at the first blank line.
std::vector<std::string> help_subcommands(const std::string& help) {
  static const std::regex entry("^  ([a-z][a-z0-9_-]*)( .*)?$");
  std::vector<std::string> names;
  bool inside = false;
  for (const std::string& line : lines_of(help)) {
    if (!inside) {
      inside = line.rfind("Subcommands:", 0) == 0 || line.rfind("SUBCOMMANDS:", 0) == 0;
      continue;
    }
    if (line.empty()) break;
    std::smatch m;
    if (std::regex_match(line, m, entry)) names.push_back(m[1]);
  }
  return names;
}

/// Names of the "- `name`: what" lines between the README's subcommand markers.
std::vector<std::string> readme_subcommands(const std::string& readme) {
  static const std::regex item("^- `([a-z][a-z0-9_-]*)`.*$");
  std::vector<std::string> names;
  bool inside = false;
  for (const std::string& line : lines_of(readme)) {
    if (line.find("<!-- subcommands:begin -->") != std::string::npos) inside = true;
    else if (line.find("<!-- subcommands:end -->") != std::string::npos) break;
    else if (std::smatch m; inside && std::regex_match(line, m, item)) names.push_back(m[1]);
  }
  return names;
}

TEST(CliReadme, SubcommandListMatchesHelp) {
  const auto help = test::run_cli({"--help"});
  ASSERT_EQ(help.exit_code, 0) << help.err;
  const std::vector<std::string> from_help = help_subcommands(help.out);
  ASSERT_FALSE(from_help.empty()) << "no \"Subcommands:\" section in imunoise --help:\n" << help.out;

  const std::string readme = test::slurp(IMUNOISE_README_PATH);
  ASSERT_FALSE(readme.empty()) << "cannot read " << IMUNOISE_README_PATH;
  const std::vector<std::string> from_readme = readme_subcommands(readme);
  ASSERT_FALSE(from_readme.empty()) << "no subcommand list between the README's "
                                       "<!-- subcommands:begin --> and <!-- subcommands:end --> markers";

  EXPECT_EQ(sorted(from_readme), sorted(from_help))
      << "README.md's subcommand list and `imunoise --help` disagree; update the list in README.md";
}

// The parsers themselves, on CLI11's layout and on a README fragment.
TEST(CliReadme, ParsesHelpAndReadmeLists) {
  const std::string help =
      "imunoise: noise analysis\nUsage: imunoise [OPTIONS] SUBCOMMAND\n\nOptions:\n"
      "  -h,--help                   Print this help message and exit\n\nSubcommands:\n"
      "  dev                         deviation curves\n"
      "                              continued description\n"
      "  fit                         noise terms\n\n";
  EXPECT_EQ(help_subcommands(help), (std::vector<std::string>{"dev", "fit"}));
  const std::string readme =
      "- `outside`: not listed\n<!-- subcommands:begin -->\n- `dev`: curves\n"
      "- `fit`: terms\n<!-- subcommands:end -->\n- `after`: not listed\n";
  EXPECT_EQ(readme_subcommands(readme), (std::vector<std::string>{"dev", "fit"}));
}

}  // namespace
}  // namespace imunoise
