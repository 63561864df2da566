#include "imunoise/fleet/study_files.hpp"

#include <string>

#include "imunoise/error.hpp"
#include "imunoise/fleet/outcome_wire.hpp"
#include "imunoise/parallel/task_farm.hpp"

namespace imunoise::fleet {
namespace {

[[noreturn]] void fail_strict(const SensorOutcome& outcome) {
  throw InputError(outcome.error + " (--strict: the fleet run stops at the first failed file; "
                   "without it the file is reported and the run goes on)");
}

}  // namespace

std::vector<SensorOutcome> study_files(parallel::Ranks& ranks, std::span<const load::LoadOptions> inputs,
                                       const study::SensorOptions& options, const StudyFilesOptions& run) {
  std::vector<SensorOutcome> results(inputs.size());
  std::vector<std::string> files;
  for (const auto& input : inputs) files.push_back(input.file);
  const SensorOutcome* first_failure = nullptr;
  const auto study = [&](std::size_t i) {
    if (run.before_file) run.before_file(i);
    return study_file(inputs[i], options);
  };
  // A failure on rank 0: reported and the run goes on, or (strict) the end of the hand-out.
  const auto take = [&](SensorOutcome outcome, std::size_t index) {
    results[index] = std::move(outcome);
    if (results[index].ok()) return true;
    if (run.strict) {
      if (first_failure == nullptr) first_failure = &results[index];
      return false;
    }
    if (run.on_failure) run.on_failure(results[index]);
    return true;
  };
  if (ranks.size() == 1) {
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      if (!take(study(i), i)) break;
    }
  } else {
    parallel::run_task_farm(
        ranks, inputs.size(), [&](std::size_t i) { return encode_outcome(i, study(i)); },
        [&](std::size_t, const parallel::Bytes& bytes) {
          SensorOutcome outcome;
          const std::size_t index = decode_outcome(bytes, files, outcome);
          return take(std::move(outcome), index) && first_failure == nullptr;
        });
    if (ranks.rank() != 0) return {};
  }
  if (first_failure != nullptr) fail_strict(*first_failure);
  return results;
}

}  // namespace imunoise::fleet
