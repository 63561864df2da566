#pragma once
// What a terminal shows of a study: one line per channel (what was fitted, what the record
// could not support, which terms were added automatically, how many diagnostics the report
// holds), so that six channels take six lines; the diagnostics themselves are in the report.
#include <string>

#include "imunoise/study/study.hpp"

namespace imunoise::study {

/// "gyro_x: fitted N B K; not identified: Q R; added automatically: Gauss-Markov (T_c 196 s);
/// 3 diagnostics in the report", or "gyro_x failed: ..." for a channel that failed.
std::string channel_summary(const ChannelStudy& channel);

}  // namespace imunoise::study
