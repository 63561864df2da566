#pragma once
// The fleet's work over the ranks: every file studied once (fleet::study_file), serially on
// one rank, or handed out by rank 0 to ranks 1..P-1 as they become free (parallel/task_farm.hpp),
// the results in the files' order either way, so the outputs are the serial run's bytes.
// A failed file is reported to `on_failure` and the run goes on; with `strict` the run stops
// at the first failure (files already running still finish) with an InputError saying so.
#include <functional>
#include <span>
#include <vector>

#include "imunoise/fleet/fleet.hpp"
#include "imunoise/parallel/ranks.hpp"

namespace imunoise::fleet {

struct StudyFilesOptions {
  bool strict = false;
  /// Called on rank 0 for each failed file (when not strict), in completion order.
  std::function<void(const SensorOutcome&)> on_failure;
  /// Called on the rank that studies file i just before (a hook for tests that kill a rank).
  std::function<void(std::size_t)> before_file;
};

/// Rank 0 returns every outcome (one per input, in order); the other ranks an empty list.
std::vector<SensorOutcome> study_files(parallel::Ranks& ranks, std::span<const load::LoadOptions> inputs,
                                       const study::SensorOptions& options, const StudyFilesOptions& run = {});

}  // namespace imunoise::fleet
