// PLACEHOLDER until the simulator lands (being written now): replace this whole file.
#include "commands.hpp"
namespace imunoise::cli { void setup_simulate(CLI::App&) {} }
