// imunoise command line: noise analysis of inertial sensors.
#include <algorithm>
#include <array>
#include <cstdio>
#include <exception>
#include <new>
#include <string>
#include <string_view>

#include <fmt/core.h>

#include "commands.hpp"
#include "imunoise/error.hpp"
#include "mpi_session.hpp"

namespace {

constexpr std::string_view kVersion = "imunoise 0.1.0";

struct Command {
  std::string_view name;
  void (*setup)(CLI::App&);
};

constexpr std::array kCommands{
    Command{"dev", imunoise::cli::setup_dev},         Command{"simulate", imunoise::cli::setup_simulate},
    Command{"fit", imunoise::cli::setup_fit},         Command{"nav", imunoise::cli::setup_nav},
    Command{"redundant", imunoise::cli::setup_redundant}, Command{"fleet", imunoise::cli::setup_fleet},
    Command{"analyze", imunoise::cli::setup_analyze}, Command{"demo", imunoise::cli::setup_demo},
    Command{"check", imunoise::cli::setup_check},
};

// Registering every command's options is most of the start-up's own work, so only the command
// named on the line (the first word that is no option: the top level has only flags) is set
// up; none for `--version` or a missing command; all for top-level help and for an unknown
// name, so that the help and the error list them as before.
void setup_commands(CLI::App& app, int argc, char** argv) {
  bool help = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      help = true;
    } else if (!arg.starts_with('-')) {
      for (const Command& command : kCommands) {
        if (!help && command.name == arg) return command.setup(app);
      }
      break;
    }
  }
  const bool named = std::any_of(argv + 1, argv + argc, [](const char* a) { return a[0] != '-'; });
  if (!help && !named) return;
  for (const Command& command : kCommands) command.setup(app);
}

}  // namespace

int main(int argc, char** argv) {
  // `imunoise --version` alone is answered before CLI11 is built: its version flag answers by
  // throwing, and the first throw of a process pages in the unwinder and the exception tables
  // (about 10 page faults, 0.3 ms on a VM where a fault costs 26 us; docs/performance.md).
  if (argc == 2 && std::string_view(argv[1]) == "--version") {
    fmt::print("{}\n", kVersion);
    return 0;
  }
  try {
    imunoise::cli::mpi::hand_over_to_mpi_build(argv);
  } catch (const imunoise::InputError& e) {
    fmt::print(stderr, "imunoise: error: {}\n", e.what());
    return 1;
  }
  CLI::App app{"imunoise: noise analysis of inertial sensors (Allan family, noise model, navigation error)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(kVersion));
  setup_commands(app, argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 reports usage errors with its own exit codes; the contract says 1 for bad arguments.
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  } catch (const imunoise::InputError& e) {
    fmt::print(stderr, "imunoise: error: {}\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "imunoise: internal error: out of memory\n");
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "imunoise: internal error: {}\n", e.what());
    return 2;
  }
  return 0;
}
