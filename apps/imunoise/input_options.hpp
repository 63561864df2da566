#pragma once
// The command-line binding of the loader's options (imunoise/load/load.hpp): one binder for
// every subcommand that reads a file, so each accepts the same options with the same meaning.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "imunoise/load/load.hpp"

namespace imunoise::cli {

using InputOptions = load::LoadOptions;

/// Registers the positional `file` and every input option (--rate, --units, --column,
/// --time-column, containers, preprocessing, binary layout, scaling) on `command`.
void add_input_options(CLI::App& command, load::LoadOptions& options);

/// As add_input_options without the positional file: for commands whose files come in an
/// option of their own (redundant --fuse).
void add_load_options(CLI::App& command, load::LoadOptions& options);

/// The inputs of a command that studies many channels (analyze, fleet): the files, the value
/// columns of each, and the options shared by all of them.
struct MultiInputOptions {
  std::vector<std::string> files;
  std::string columns;    ///< a,b,c: names or 0-based indexes; empty: every value channel
  load::LoadOptions load;  ///< shared by every file (file and column are set per channel)
};

/// As add_input_options, with the positional `files` (one or more) and --columns instead of
/// `file` and --column. `files_help` describes the positional.
void add_multi_input_options(CLI::App& command, MultiInputOptions& options, const std::string& files_help);

/// Prints what the loader decided on the user's behalf (Record::notes) on standard error.
void print_load_notes(const Record& record);

}  // namespace imunoise::cli
