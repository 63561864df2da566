#include "imunoise/study/summary.hpp"

#include <fmt/core.h>

namespace imunoise::study {

std::string channel_summary(const ChannelStudy& ch) {
  if (!ch.error.empty()) return fmt::format("{} failed: {}", ch.record.name, ch.error);
  std::string text = ch.record.name + ":";
  if (ch.fit) {
    std::string fitted, missing;
    for (int j = 0; j < fit::kTermCount; ++j) {
      if (!ch.fit->terms[j].fitted) continue;
      std::string& list = fit::coefficient(ch.fit->coefficients, j).identified ? fitted : missing;
      list += (list.empty() ? "" : " ") + std::string(fit::term_name(j));
    }
    text += fitted.empty() ? " no term identified" : " fitted " + fitted;
    if (!missing.empty()) text += "; not identified: " + missing;
    const auto& x = ch.fit->extras;
    std::string added;
    const auto& c = ch.fit->coefficients;
    if (x.gauss_markov.selected && !c.gauss_markov.empty()) {
      added += fmt::format("Gauss-Markov (T_c {:.3g} s)", c.gauss_markov.front().correlation_time_s.value);
    }
    if (x.sinusoid.selected && c.sinusoid) {
      added += fmt::format("{}sinusoid ({:.4g} Hz)", added.empty() ? "" : ", ", c.sinusoid->frequency_hz.value);
    }
    if (!added.empty()) text += (x.automatic ? "; added automatically: " : "; with ") + added;
  }
  if (!ch.warnings.empty()) {
    text += fmt::format("; {} diagnostic{} in the report", ch.warnings.size(), ch.warnings.size() == 1 ? "" : "s");
  }
  return text;
}

}  // namespace imunoise::study
