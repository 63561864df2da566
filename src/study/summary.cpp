#include "imunoise/study/summary.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <string_view>

namespace imunoise::study {

namespace {

// The terms of a gmwm model name such as "N+K+GM+GM+SIN".
bool in_model(std::string_view model, std::string_view term) {
  for (std::size_t start = 0; start <= model.size();) {
    const std::size_t end = std::min(model.find('+', start), model.size());
    if (model.substr(start, end - start) == term) return true;
    start = end + 1;
  }
  return false;
}

}  // namespace

std::string channel_summary(const ChannelStudy& ch) {
  if (!ch.error.empty()) return fmt::format("{} failed: {}", ch.record.name, ch.error);
  std::string text = ch.record.name + ":";
  if (ch.fit) {
    // gmwm: a term outside the selected model was not tried, so it is not "not identified".
    const std::string_view model = ch.fit->gmwm ? std::string_view(ch.fit->gmwm->model) : std::string_view();
    std::string fitted, missing;
    for (int j = 0; j < fit::kTermCount; ++j) {
      if (!ch.fit->terms[j].fitted) continue;
      if (!model.empty() && !in_model(model, fit::term_name(j))) continue;
      std::string& list = fit::coefficient(ch.fit->coefficients, j).identified ? fitted : missing;
      list += (list.empty() ? "" : " ") + std::string(fit::term_name(j));
    }
    text += fitted.empty() ? " no term identified" : " fitted " + fitted;
    if (!missing.empty()) text += "; not identified: " + missing;
    const auto& x = ch.fit->extras;
    std::string added;
    const auto& c = ch.fit->coefficients;
    if (!model.empty()) {
      // gmwm: its GM and SIN terms are part of the selected model, not automatic extras.
      std::string times;
      std::size_t weak = 0;
      for (const auto& gm : c.gauss_markov) {
        if (!gm.correlation_time_s.identified) {
          ++weak;
          continue;
        }
        times += fmt::format("{}{:.3g}", times.empty() ? "" : ", ", gm.correlation_time_s.value);
      }
      text += fmt::format("; gmwm model {}", model);
      std::string parts;
      if (!times.empty()) parts += "GM T_c " + times + " s";
      if (weak > 0) parts += fmt::format("{}{} GM not significant", parts.empty() ? "" : "; ", weak);
      if (c.sinusoid && c.sinusoid->frequency_hz.identified) {
        parts += fmt::format("{}SIN {:.4g} Hz", parts.empty() ? "" : "; ", c.sinusoid->frequency_hz.value);
      }
      if (!parts.empty()) text += " (" + parts + ")";
    } else if (x.gauss_markov.selected && !c.gauss_markov.empty()) {
      added += fmt::format("Gauss-Markov (T_c {:.3g} s)", c.gauss_markov.front().correlation_time_s.value);
    }
    if (model.empty() && x.sinusoid.selected && c.sinusoid) {
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
