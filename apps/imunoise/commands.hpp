#pragma once
// Each subcommand lives in its own file: setup_<cmd> registers its options on the app and
// the callback that runs it. main() only wires them and turns exceptions into exit codes.
#include <CLI/CLI.hpp>

namespace imunoise::cli {

void setup_dev(CLI::App& app);
void setup_simulate(CLI::App& app);
void setup_fit(CLI::App& app);
void setup_nav(CLI::App& app);
void setup_redundant(CLI::App& app);
void setup_fleet(CLI::App& app);
void setup_analyze(CLI::App& app);
void setup_demo(CLI::App& app);
void setup_check(CLI::App& app);

}  // namespace imunoise::cli
