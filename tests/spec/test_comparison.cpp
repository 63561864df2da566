// Datasheet comparison with the paper's numbers (Table 2 against the TG-100 datasheet).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "imunoise/error.hpp"
#include "imunoise/spec/comparison.hpp"

namespace imunoise {
namespace {

constexpr double deg = std::numbers::pi / 180.0;

Coefficient coefficient(double value_si, double rel_halfwidth = 0.0) {
  Coefficient c;
  c.value = value_si;
  c.identified = true;
  if (rel_halfwidth > 0.0) {
    c.ci_low = value_si * (1.0 - rel_halfwidth);
    c.ci_high = value_si * (1.0 + rel_halfwidth);
  }
  return c;
}

// Table 2 of the paper (deg/s units x 1e-4), converted to SI.
NoiseCoefficients table2_gyro(double n, double b, double k, double rel_ci = 0.0) {
  NoiseCoefficients c;
  c.random_walk = coefficient(n * 1e-4 * deg, rel_ci);
  c.bias_instability = coefficient(b * 1e-4 * deg, rel_ci);
  c.rate_random_walk = coefficient(k * 1e-4 * deg, rel_ci);
  c.quantization.note = "no -1 slope";
  return c;
}

const ComparisonRow& row(const SpecComparison& c, char symbol) {
  for (const auto& r : c.rows) {
    if (r.symbol == symbol) return r;
  }
  throw std::runtime_error("no row");
}

TEST(Comparison, PaperGyro1AgainstTg100) {
  const auto result = compare(table2_gyro(8.9, 5.9, 0.15), builtin_spec("tg100"));
  EXPECT_EQ(result.spec_name, "tg100");
  ASSERT_EQ(result.rows.size(), 3u);  // N, B from the spec; K identified but not rated

  const auto& b = row(result, 'B');
  EXPECT_EQ(b.term, "bias_instability");
  EXPECT_NEAR(b.measured_customary.value, 2.124, 1e-9);  // 5.9e-4 deg/s x 3600
  EXPECT_EQ(b.measured_customary.unit, "deg/h");
  EXPECT_NEAR(b.measured_spec_unit.value, 2.124, 1e-9);
  EXPECT_EQ(b.measured_spec_unit.unit, "deg/h");
  EXPECT_EQ(b.spec_value, 2.0);
  EXPECT_NEAR(b.deviation_percent, 6.2, 1e-9);  // the paper: "6 %"
  EXPECT_EQ(b.verdict, Verdict::fail);

  const auto& n = row(result, 'N');
  EXPECT_NEAR(n.measured_customary.value, 0.0534, 1e-12);  // 8.9e-4 x 60
  EXPECT_EQ(n.measured_customary.unit, "deg/sqrt(h)");
  EXPECT_NEAR(n.measured_si.value, 1.553e-5, 0.0005e-5);  // references.md
  EXPECT_NEAR(n.deviation_percent, 6.8, 1e-9);            // the paper: "up to 6 %"
  EXPECT_EQ(n.verdict, Verdict::fail);

  const auto& k = row(result, 'K');
  EXPECT_EQ(k.verdict, Verdict::not_in_spec);
  EXPECT_TRUE(std::isnan(k.deviation_percent));
  EXPECT_NEAR(k.measured_customary.value, 0.15e-4 * 216000, 1e-9);  // deg/h/sqrt(h)
  EXPECT_FALSE(result.all_pass);
}

TEST(Comparison, PaperGyro3Bias) {
  const auto result = compare(table2_gyro(8.8, 5.8, 0.09), builtin_spec("tg100"));
  const auto& b = row(result, 'B');
  EXPECT_NEAR(b.measured_customary.value, 2.088, 1e-9);
  EXPECT_NEAR(b.deviation_percent, 4.4, 1e-9);                 // the paper: "4.5 %"
  EXPECT_NEAR(row(result, 'N').deviation_percent, 5.6, 1e-9);  // 8.8e-4 x 60 = 0.0528
}

TEST(Comparison, ToleranceMakesItPassAndCiDecidesConclusiveness) {
  Spec spec = builtin_spec("tg100");
  spec.bias_instability->tolerance = 0.10;  // pass if B <= 2.2 deg/h
  spec.random_walk->tolerance = 0.10;       // pass if N <= 0.055 deg/sqrt(h)
  // CI +/-1 %: B in [2.103, 2.145] below 2.2 (conclusive pass);
  // N in [0.05287, 0.05393] below 0.055 (conclusive pass).
  auto narrow = compare(table2_gyro(8.9, 5.9, 0.15, 0.01), spec);
  EXPECT_EQ(row(narrow, 'B').verdict, Verdict::pass);
  EXPECT_EQ(row(narrow, 'B').ci_position, CiPosition::below);
  EXPECT_TRUE(row(narrow, 'B').conclusive);
  EXPECT_NEAR(row(narrow, 'B').limit_si, 2.2 * deg / 3600.0, 1e-20);
  EXPECT_TRUE(narrow.all_pass);
  // CI +/-10 %: B in [1.91, 2.34] straddles 2.2: a pass, but inconclusive.
  auto wide = compare(table2_gyro(8.9, 5.9, 0.15, 0.10), spec);
  EXPECT_EQ(row(wide, 'B').verdict, Verdict::pass);
  EXPECT_EQ(row(wide, 'B').ci_position, CiPosition::straddles);
  EXPECT_FALSE(row(wide, 'B').conclusive);
  // Against the raw datasheet (tolerance 0) a +/-1 % CI lies entirely above: conclusive fail.
  auto strict = compare(table2_gyro(8.9, 5.9, 0.15, 0.01), builtin_spec("tg100"));
  EXPECT_EQ(row(strict, 'B').ci_position, CiPosition::above);
  EXPECT_TRUE(row(strict, 'B').conclusive);
  EXPECT_NEAR(row(strict, 'B').measured_spec_unit.ci_low, 2.124 * 0.99, 1e-9);
}

TEST(Comparison, NotIdentifiedAndNoInterval) {
  NoiseCoefficients c = table2_gyro(8.9, 5.9, 0.15);
  c.bias_instability = Coefficient{};
  c.bias_instability.note = "no floor in the record";
  c.rate_random_walk = Coefficient{};
  const auto result = compare(c, builtin_spec("tg100"));
  ASSERT_EQ(result.rows.size(), 2u);  // K neither identified nor rated: no row
  const auto& b = row(result, 'B');
  EXPECT_EQ(b.verdict, Verdict::not_identified);
  EXPECT_TRUE(std::isnan(b.measured_customary.value));
  EXPECT_EQ(b.note, "no floor in the record");
  EXPECT_EQ(row(result, 'N').ci_position, CiPosition::unknown);
  EXPECT_FALSE(row(result, 'N').conclusive);
  EXPECT_FALSE(result.all_pass);
}

TEST(Comparison, OneSidedDensityIsComparedInItsOwnConvention) {
  // Spec: one-sided density 1.2e-3 deg/s/sqrt(Hz) => N limit = 1.2e-3/sqrt(2) deg/sqrt(s).
  const Spec spec = parse_spec_yaml(
      "name: d\nsensor: gyroscope\nterms:\n  random_walk: {value: 1.2e-3, unit: deg/s/sqrt(Hz), "
      "psd: one_sided}\n",
      "d.yaml");
  const auto result = compare(table2_gyro(8.9, 5.9, 0.15), spec);
  const auto& n = row(result, 'N');
  EXPECT_NEAR(n.measured_spec_unit.value, 8.9e-4 * std::numbers::sqrt2, 1e-15);
  EXPECT_EQ(n.measured_spec_unit.unit, "deg/s/sqrt(Hz)");
  EXPECT_EQ(n.psd, "one_sided");
  EXPECT_NEAR(n.deviation_percent, 100.0 * (8.9e-4 * std::numbers::sqrt2 / 1.2e-3 - 1.0), 1e-9);
  EXPECT_EQ(n.verdict, Verdict::fail);  // 1.2587e-3 > 1.2e-3
}

TEST(Comparison, AccelerometerCustomaryUnitsAndKindMismatch) {
  const Spec spec = parse_spec_yaml(
      "name: acc\nsensor: accelerometer\nterms:\n  bias_instability: {value: 20, unit: ug}\n",
      "acc.yaml");
  NoiseCoefficients c;
  c.quantity = Quantity::acceleration;
  c.bias_instability = coefficient(19e-6 * 9.80665);
  const auto result = compare(c, spec);
  const auto& b = row(result, 'B');
  EXPECT_NEAR(b.measured_customary.value, 19.0, 1e-9);
  EXPECT_EQ(b.measured_customary.unit, "ug");
  EXPECT_NEAR(b.deviation_percent, -5.0, 1e-9);
  EXPECT_EQ(b.verdict, Verdict::pass);
  EXPECT_TRUE(result.all_pass);
  // A gyro fit against an accelerometer spec is an input error.
  EXPECT_THROW((void)compare(table2_gyro(8.9, 5.9, 0.15), spec), InputError);
}

}  // namespace
}  // namespace imunoise
