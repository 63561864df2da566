#pragma once
// A loaded file (PhaseRecord) handed to the library's study stages as a study::Record.
#include <string>

#include "imunoise/study/record.hpp"
#include "input_options.hpp"

namespace imunoise::cli {

/// Moves the samples; `name` is the channel name in reports (empty: the source).
study::Record to_study_record(PhaseRecord&& record, std::string name = {});

}  // namespace imunoise::cli
