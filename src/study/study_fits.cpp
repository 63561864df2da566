#include "imunoise/study/study_fits.hpp"

#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise::study {

StudyFits study_fits(const Study& study) {
  StudyFits out;
  for (const auto& ch : study.channels) {
    if (!ch.fit) continue;
    out.fits.push_back(exports::axis_fit(ch.record, ch.fit->coefficients));
    out.fits.back().channel = ch.record.name;
    if (out.sources.find(ch.record.source) == std::string::npos) {
      out.sources += (out.sources.empty() ? "" : ", ") + ch.record.source;
    }
    if (out.rate_hz == 0.0) out.rate_hz = ch.record.rate_hz;
    if (ch.record.rate_hz != out.rate_hz) {
      throw InputError(fmt::format("--export: channel {} is sampled at {:g} Hz and the others at {:g} Hz; a filter "
                                   "file has one rate; fix: export from channels of one rate",
                                   ch.record.name, ch.record.rate_hz, out.rate_hz));
    }
  }
  return out;
}

}  // namespace imunoise::study
