// The demo's acceptance: the four simulated TG-100 gyros (Table 2, 200 Hz, 6 h, the demo's
// fixed seed) give back the coefficients they were simulated with. Tolerances: N within 2 %
// (its relative standard error on 6 h at 200 Hz is about 0.1-0.3 %, docs/fit.md), B within
// 10 % (the flicker floor's estimate spreads by a few percent over the octaves it dominates),
// and K's 95 % interval contains the truth. Slow (about 30 s in Release): excluded from the
// sanitizer run by its name.
#include <gtest/gtest.h>

#include <cmath>

#include "imunoise/sim/presets.hpp"
#include "imunoise/study/demo.hpp"

namespace imunoise {
namespace {

TEST(SlowDemo, RecoversTable2) {
  const study::DemoOptions demo;
  const auto result = study::run_study(study::simulate_demo_records(demo), study::demo_study_options());
  const auto doc_reference = study::demo_reference(result, demo);
  const auto preset = sim::find_preset("tg100");
  ASSERT_EQ(result.channels.size(), 4u);
  const double deg = parse_unit("deg/s").to_si;
  for (std::size_t c = 0; c < 4; ++c) {
    const auto& truth = preset.channels[c].noise;
    const auto& fit = result.channels[c].fit;
    ASSERT_TRUE(fit.has_value()) << c;
    const auto& k = fit->coefficients;
    ASSERT_TRUE(k.random_walk.identified) << c;
    EXPECT_NEAR(k.random_walk.value / deg, truth.n_unit_sqrt_s, 0.02 * truth.n_unit_sqrt_s) << c;
    ASSERT_TRUE(k.bias_instability.identified) << c;
    EXPECT_NEAR(k.bias_instability.value / deg, truth.b_unit, 0.10 * truth.b_unit) << c;
    EXPECT_LE(k.rate_random_walk.ci_low / deg, truth.k_unit_per_sqrt_s) << c;
    EXPECT_GE(k.rate_random_walk.ci_high / deg, truth.k_unit_per_sqrt_s) << c;
  }
  // The reference table the report shows holds the same numbers.
  ASSERT_EQ(doc_reference["rows"].size(), 16u);
  const auto& n1 = doc_reference["rows"][0];
  EXPECT_EQ(n1["term"], "N");
  EXPECT_DOUBLE_EQ(n1["recovered"].get<double>(),
                   result.channels[0].fit->coefficients.random_walk.value / deg);
  EXPECT_DOUBLE_EQ(n1["paper"].get<double>(), 8.9e-4);
}

}  // namespace
}  // namespace imunoise
