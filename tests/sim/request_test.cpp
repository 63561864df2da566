// plan_simulation: the request checks that need the whole request, and the output stage.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "imunoise/error.hpp"
#include "imunoise/sim/presets.hpp"
#include "imunoise/sim/request.hpp"

namespace imunoise::sim {
namespace {

std::string error_of(const SimulationRequest& r) {
  try {
    plan_simulation(r);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

SimulationRequest plain() {
  SimulationRequest r;
  r.rate_hz = 100.0;
  r.noise.n_unit_sqrt_s = 1e-3;
  return r;
}

TEST(SimulationRequest, PlainModelOnEveryChannelWithoutRange) {
  SimulationRequest r = plain();
  r.channels = 3;
  const SimulationPlan p = plan_simulation(r);
  EXPECT_EQ(p.unit, "deg/s");
  EXPECT_EQ(p.output_unit, "deg/s");
  ASSERT_EQ(p.spec.channels.size(), 3U);
  for (const ChannelSpec& c : p.spec.channels) {
    EXPECT_EQ(c.noise.n_unit_sqrt_s, 1e-3);
    EXPECT_TRUE(std::isinf(c.output.range_unit));
  }
}

TEST(SimulationRequest, PresetKeepsItsRangeRateAndUnitUnlessGiven) {
  SimulationRequest r;
  r.preset = "tg100";
  const Preset tg100 = find_preset("tg100");
  const SimulationPlan p = plan_simulation(r);
  EXPECT_EQ(p.spec.rate_hz, tg100.rate_hz);
  EXPECT_EQ(p.unit, tg100.unit);
  ASSERT_EQ(p.spec.channels.size(), tg100.channels.size());
  EXPECT_EQ(p.spec.channels[0].output.range_unit, tg100.channels[0].output.range_unit);
  r.range_unit = 50.0;
  r.rate_hz = 400.0;
  const SimulationPlan q = plan_simulation(r);
  EXPECT_EQ(q.spec.channels[0].output.range_unit, 50.0);
  EXPECT_EQ(q.spec.rate_hz, 400.0);
}

TEST(SimulationRequest, AnalogAndScaledOutputUnits) {
  SimulationRequest r = plain();
  r.volts_per_unit = 0.02;
  r.scale_factor = 1.001;
  const SimulationPlan p = plan_simulation(r);
  EXPECT_EQ(p.output_unit, "V");
  EXPECT_DOUBLE_EQ(p.spec.channels[0].output.scale_factor, 1.001 * 0.02);
  r.volts_per_unit = 0.0;
  EXPECT_EQ(plan_simulation(r).output_unit, "deg/s (scaled)");
}

TEST(SimulationRequest, ConflictsAndMissingValuesNameTheOptionAndTheFix) {
  SimulationRequest preset;
  preset.preset = "tg100";
  preset.noise_given = {"--K"};
  EXPECT_NE(error_of(preset).find("--K cannot be combined with --preset tg100"), std::string::npos);
  preset.noise_given.clear();
  preset.channels = 2;
  EXPECT_NE(error_of(preset).find("--channels cannot be combined"), std::string::npos);
  preset.channels.reset();
  preset.unit = "rad/s";
  EXPECT_NE(error_of(preset).find("drop --units or give --units"), std::string::npos);
  preset.unit = "deg/s";
  EXPECT_EQ(error_of(preset), "");

  SimulationRequest r = plain();
  r.rate_hz.reset();
  EXPECT_NE(error_of(r).find("--rate HZ is required"), std::string::npos);
  r = plain();
  r.unit = "deg";
  EXPECT_NE(error_of(r).find("is not a rate unit"), std::string::npos);
  r = plain();
  r.channels = 0;
  EXPECT_NE(error_of(r).find("at least 1"), std::string::npos);
  r = plain();
  r.volts_per_unit = -1.0;
  EXPECT_NE(error_of(r).find("--volts-per-unit must be positive"), std::string::npos);
}

}  // namespace
}  // namespace imunoise::sim
