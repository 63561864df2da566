// imunoise command line: noise analysis of inertial sensors.
#include <cstdio>
#include <exception>
#include <new>

#include <fmt/core.h>

#include "commands.hpp"
#include "imunoise/error.hpp"
#include "mpi_session.hpp"

int main(int argc, char** argv) {
  try {
    imunoise::cli::mpi::hand_over_to_mpi_build(argv);
  } catch (const imunoise::InputError& e) {
    fmt::print(stderr, "imunoise: error: {}\n", e.what());
    return 1;
  }
  CLI::App app{"imunoise: noise analysis of inertial sensors (Allan family, noise model, navigation error)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "imunoise 0.1.0");
  imunoise::cli::setup_dev(app);
  imunoise::cli::setup_simulate(app);
  imunoise::cli::setup_fit(app);
  imunoise::cli::setup_nav(app);
  imunoise::cli::setup_redundant(app);
  imunoise::cli::setup_fleet(app);
  imunoise::cli::setup_analyze(app);
  imunoise::cli::setup_demo(app);
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
