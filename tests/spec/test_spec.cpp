// Spec files: the YAML format, its units and conventions, the built-in tg100, and the error
// messages for bad files (each names the file, the line, the key and the fix).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "imunoise/error.hpp"
#include "imunoise/spec/spec.hpp"

namespace imunoise {
namespace {

// From the data directory CMake names, not __FILE__: a compiler cache may make __FILE__ relative.
const std::filesystem::path kRepo = std::filesystem::path(IMUNOISE_TEST_DATA_DIR).parent_path().parent_path();

constexpr double deg = std::numbers::pi / 180.0;

void expect_rel(double actual, double expected, double rel = 1e-12) {
  EXPECT_NEAR(actual, expected, rel * std::abs(expected)) << "expected " << expected;
}

// The InputError message of parsing `yaml`, or "" when it parses.
std::string error_of(const std::string& yaml) {
  try {
    (void)parse_spec_yaml(yaml, "bad.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(BuiltinSpec, Tg100HasTable1Values) {
  const Spec s = builtin_spec("tg100");
  EXPECT_EQ(s.name, "tg100");
  EXPECT_EQ(s.sensor, SensorKind::gyroscope);
  EXPECT_EQ(s.tolerance, 0.0);
  ASSERT_TRUE(s.random_walk);
  EXPECT_EQ(s.random_walk->value, 0.05);
  EXPECT_EQ(s.random_walk->unit, "deg/sqrt(h)");
  EXPECT_EQ(s.random_walk->psd, PsdConvention::not_applicable);
  expect_rel(s.random_walk->value_si, 0.05 * deg / 60.0);
  ASSERT_TRUE(s.bias_instability);
  EXPECT_EQ(s.bias_instability->value, 2.0);
  expect_rel(s.bias_instability->value_si, 2.0 * deg / 3600.0);
  EXPECT_FALSE(s.rate_random_walk);
  ASSERT_TRUE(s.range && s.bandwidth && s.scale_factor);
  expect_rel(s.range->value_si, 100.0 * deg);
  EXPECT_EQ(s.bandwidth->value_si, 50.0);
  expect_rel(s.scale_factor->value_si, 0.020 / deg);  // V/(rad/s)
  EXPECT_EQ(builtin_spec_names(), (std::vector<std::string>{"adis16405", "tg100"}));
}

TEST(BuiltinSpec, Adis16405HasDatasheetValues) {
  const Spec s = builtin_spec("adis16405");
  EXPECT_EQ(s.name, "adis16405");
  EXPECT_EQ(s.source, "builtin:adis16405");
  EXPECT_EQ(s.sensor, SensorKind::gyroscope);
  ASSERT_TRUE(s.random_walk);
  EXPECT_EQ(s.random_walk->value, 2.0);
  EXPECT_EQ(s.random_walk->unit, "deg/sqrt(h)");
  expect_rel(s.random_walk->value_si, 2.0 * deg / 60.0);
  ASSERT_TRUE(s.bias_instability);
  EXPECT_EQ(s.bias_instability->value, 0.007);
  EXPECT_EQ(s.bias_instability->unit, "deg/s");
  expect_rel(s.bias_instability->value_si, 0.007 * deg);
  EXPECT_FALSE(s.rate_random_walk);
  ASSERT_TRUE(s.range && s.bandwidth);
  expect_rel(s.range->value_si, 300.0 * deg);
  EXPECT_EQ(s.bandwidth->value_si, 330.0);
  EXPECT_FALSE(s.scale_factor);
  // The same spec through the name-or-path resolver the CLI uses.
  EXPECT_EQ(resolve_spec("adis16405").bias_instability->value_si, s.bias_instability->value_si);
}

TEST(BuiltinSpec, UnknownNameListsKnownOnes) {
  try {
    (void)builtin_spec("tg200");
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("tg200"), std::string::npos);
    EXPECT_NE(m.find("tg100"), std::string::npos);
    EXPECT_NE(m.find("fix:"), std::string::npos);
  }
}

void expect_same_term(const std::optional<SpecTerm>& a, const std::optional<SpecTerm>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->value, b->value);
  EXPECT_EQ(a->unit, b->unit);
  EXPECT_EQ(a->psd, b->psd);
  EXPECT_EQ(a->tolerance, b->tolerance);
  EXPECT_EQ(a->value_si, b->value_si);
}

void expect_same_rating(const std::optional<SpecRating>& a, const std::optional<SpecRating>& b) {
  ASSERT_EQ(a.has_value(), b.has_value());
  if (!a) return;
  EXPECT_EQ(a->value, b->value);
  EXPECT_EQ(a->unit, b->unit);
  expect_rel(a->value_si, b->value_si, 1e-15);
}

TEST(SpecFile, ExampleTg100AgreesWithBuiltin) {
  const auto path = (kRepo / "examples" / "specs" / "tg100.yaml").string();
  const Spec file = load_spec_file(path);
  const Spec builtin = builtin_spec("tg100");
  EXPECT_EQ(file.name, builtin.name);
  EXPECT_EQ(file.description, builtin.description);
  EXPECT_EQ(file.sensor, builtin.sensor);
  EXPECT_EQ(file.tolerance, builtin.tolerance);
  EXPECT_EQ(file.source, path);
  expect_same_term(file.random_walk, builtin.random_walk);
  expect_same_term(file.bias_instability, builtin.bias_instability);
  expect_same_term(file.rate_random_walk, builtin.rate_random_walk);
  expect_same_rating(file.range, builtin.range);
  expect_same_rating(file.bandwidth, builtin.bandwidth);
  expect_same_rating(file.scale_factor, builtin.scale_factor);
}

TEST(SpecFile, ExampleAdis16405AgreesWithBuiltin) {
  const auto path = (kRepo / "examples" / "specs" / "adis16405.yaml").string();
  const Spec file = load_spec_file(path);
  const Spec builtin = builtin_spec("adis16405");
  EXPECT_EQ(file.name, builtin.name);
  EXPECT_EQ(file.description, builtin.description);
  EXPECT_EQ(file.sensor, builtin.sensor);
  EXPECT_EQ(file.tolerance, builtin.tolerance);
  EXPECT_EQ(file.source, path);
  expect_same_term(file.random_walk, builtin.random_walk);
  expect_same_term(file.bias_instability, builtin.bias_instability);
  expect_same_term(file.rate_random_walk, builtin.rate_random_walk);
  expect_same_rating(file.range, builtin.range);
  expect_same_rating(file.bandwidth, builtin.bandwidth);
  expect_same_rating(file.scale_factor, builtin.scale_factor);
}

TEST(SpecFile, NoiseDensityConventions) {
  // 0.00083333 deg/s/sqrt(Hz) two-sided is N = 0.05 deg/sqrt(h) (x 60); one-sided is sqrt(2)
  // larger for the same N.
  const double density = 0.05 / 60.0;
  const Spec two = parse_spec_yaml(
      "name: a\nsensor: gyroscope\nterms:\n  random_walk: {value: " + std::to_string(density) +
          ", unit: deg/s/sqrt(Hz), psd: two_sided}\n",
      "a.yaml");
  const Spec one = parse_spec_yaml(
      "name: a\nsensor: gyroscope\nterms:\n  random_walk: {value: " + std::to_string(density) +
          ", unit: deg/s/sqrt(Hz), psd: one_sided}\n",
      "a.yaml");
  EXPECT_EQ(two.random_walk->psd, PsdConvention::two_sided);
  expect_rel(two.random_walk->value_si, std::stod(std::to_string(density)) * deg);
  expect_rel(one.random_walk->value_si, two.random_walk->value_si / std::numbers::sqrt2);
}

TEST(SpecFile, UnitConversionsToSi) {
  const double g = 9.80665;
  // gyro N
  expect_rel(
      spec_term_to_si('N', SensorKind::gyroscope, "deg/sqrt(h)", PsdConvention::not_applicable),
      deg / 60.0);
  expect_rel(
      spec_term_to_si('N', SensorKind::gyroscope, "deg/sqrt(s)", PsdConvention::not_applicable),
      deg);
  expect_rel(
      spec_term_to_si('N', SensorKind::gyroscope, "rad/s/sqrt(Hz)", PsdConvention::two_sided), 1.0);
  expect_rel(
      spec_term_to_si('N', SensorKind::gyroscope, "deg/h/sqrt(Hz)", PsdConvention::two_sided),
      deg / 3600.0);
  // gyro B, K
  expect_rel(spec_term_to_si('B', SensorKind::gyroscope, "deg/h", PsdConvention::not_applicable),
             deg / 3600.0);
  expect_rel(
      spec_term_to_si('K', SensorKind::gyroscope, "deg/h/sqrt(h)", PsdConvention::not_applicable),
      deg / 3600.0 / 60.0);
  expect_rel(
      spec_term_to_si('K', SensorKind::gyroscope, "rad/s^2/sqrt(Hz)", PsdConvention::two_sided),
      1.0);
  // accelerometer N (ug/sqrt(Hz), mg/sqrt(Hz), m/s/sqrt(h)), B (mg, ug), K
  expect_rel(
      spec_term_to_si('N', SensorKind::accelerometer, "ug/sqrt(Hz)", PsdConvention::two_sided),
      g * 1e-6);
  expect_rel(
      spec_term_to_si('N', SensorKind::accelerometer, "mg/sqrt(Hz)", PsdConvention::one_sided),
      g * 1e-3 / std::numbers::sqrt2);
  expect_rel(
      spec_term_to_si('N', SensorKind::accelerometer, "m/s/sqrt(h)", PsdConvention::not_applicable),
      1.0 / 60.0);
  expect_rel(spec_term_to_si('B', SensorKind::accelerometer, "mg", PsdConvention::not_applicable),
             g * 1e-3);
  expect_rel(spec_term_to_si('B', SensorKind::accelerometer, "ug", PsdConvention::not_applicable),
             g * 1e-6);
  expect_rel(
      spec_term_to_si('K', SensorKind::accelerometer, "m/s^3/sqrt(Hz)", PsdConvention::two_sided),
      1.0);
  EXPECT_TRUE(is_noise_density_unit("ug/sqrt(Hz)"));
  EXPECT_FALSE(is_noise_density_unit("deg/sqrt(h)"));
}

TEST(SpecFile, AccelerometerSpecWithToleranceAndRatings) {
  const Spec s = parse_spec_yaml(R"(name: acc
sensor: accelerometer
tolerance: 0.1
terms:
  random_walk: {value: 60, unit: ug/sqrt(Hz), psd: one_sided}
  bias_instability: {value: 20, unit: ug, tolerance: 0.25}
  rate_random_walk: {value: 3, unit: ug/sqrt(h)}
range: {value: 8, unit: g}
bandwidth: {value: 1, unit: kHz}
scale_factor: {value: 400, unit: mV/g}
)",
                                 "acc.yaml");
  EXPECT_EQ(s.sensor, SensorKind::accelerometer);
  EXPECT_EQ(s.random_walk->tolerance, 0.1);
  EXPECT_EQ(s.bias_instability->tolerance, 0.25);
  expect_rel(s.random_walk->value_si, 60e-6 * 9.80665 / std::numbers::sqrt2);
  expect_rel(s.rate_random_walk->value_si, 3e-6 * 9.80665 / 60.0);
  expect_rel(s.range->value_si, 8 * 9.80665);
  EXPECT_EQ(s.bandwidth->value_si, 1000.0);
  expect_rel(s.scale_factor->value_si, 0.4 / 9.80665);
}

// ---- bad files ----------------------------------------------------------------------------

TEST(SpecFileErrors, MissingKeyNamesKeyAndFix) {
  const std::string m = error_of("name: x\nsensor: gyroscope\n");
  EXPECT_NE(m.find("bad.yaml:1"), std::string::npos) << m;
  EXPECT_NE(m.find("'terms'"), std::string::npos) << m;
  EXPECT_NE(m.find("missing"), std::string::npos) << m;
  EXPECT_NE(m.find("fix:"), std::string::npos) << m;

  const std::string u =
      error_of("name: x\nsensor: gyroscope\nterms:\n  random_walk:\n    value: 1\n");
  EXPECT_NE(u.find("bad.yaml:5"), std::string::npos) << u;
  EXPECT_NE(u.find("'terms.random_walk.unit'"), std::string::npos) << u;
  EXPECT_NE(u.find("deg/sqrt(h)"), std::string::npos) << u;  // the fix lists units
}

TEST(SpecFileErrors, WrongUnitNamesLineKeyAndAcceptedUnits) {
  const std::string m = error_of(
      "name: x\nsensor: gyroscope\nterms:\n  bias_instability:\n    value: 2\n    unit: mg\n");
  EXPECT_NE(m.find("bad.yaml:6"), std::string::npos) << m;
  EXPECT_NE(m.find("'terms.bias_instability.unit'"), std::string::npos) << m;
  EXPECT_NE(m.find("'mg'"), std::string::npos) << m;
  EXPECT_NE(m.find("fix: use one of deg/h"), std::string::npos) << m;

  const std::string n = error_of(
      "name: x\nsensor: gyroscope\nterms:\n  random_walk: {value: 2, unit: deg/sqrt(hour)}\n");
  EXPECT_NE(n.find("bad.yaml:4"), std::string::npos) << n;
  EXPECT_NE(n.find("deg/sqrt(hour)"), std::string::npos) << n;

  const std::string r = error_of(
      "name: x\nsensor: gyroscope\nterms:\n  bias_instability: "
      "{value: 2, unit: deg/h}\nrange: {value: 100, unit: g}\n");
  EXPECT_NE(r.find("bad.yaml:5"), std::string::npos) << r;
  EXPECT_NE(r.find("'range.unit'"), std::string::npos) << r;
}

TEST(SpecFileErrors, NegativeOrTextValue) {
  const std::string m = error_of(
      "name: x\nsensor: gyroscope\nterms:\n  bias_instability:\n    value: -2\n    unit: deg/h\n");
  EXPECT_NE(m.find("bad.yaml:5"), std::string::npos) << m;
  EXPECT_NE(m.find("'terms.bias_instability.value'"), std::string::npos) << m;
  EXPECT_NE(m.find("positive"), std::string::npos) << m;
  EXPECT_NE(m.find("fix:"), std::string::npos) << m;

  const std::string t = error_of(
      "name: x\nsensor: gyroscope\nterms:\n  bias_instability:\n    value: 2 deg/h\n    unit: "
      "deg/h\n");
  EXPECT_NE(t.find("bad.yaml:5"), std::string::npos) << t;
  EXPECT_NE(t.find("not a number"), std::string::npos) << t;

  const std::string tol = error_of(
      "name: x\nsensor: gyroscope\ntolerance: -0.1\nterms:\n"
      "  bias_instability: {value: 2, unit: deg/h}\n");
  EXPECT_NE(tol.find("bad.yaml:3"), std::string::npos) << tol;
  EXPECT_NE(tol.find("'tolerance'"), std::string::npos) << tol;
}

TEST(SpecFileErrors, UnknownOrMissingConvention) {
  const std::string m = error_of(
      "name: x\nsensor: gyroscope\nterms:\n  random_walk:\n"
      "    value: 0.001\n    unit: deg/s/sqrt(Hz)\n    psd: single\n");
  EXPECT_NE(m.find("bad.yaml:7"), std::string::npos) << m;
  EXPECT_NE(m.find("'terms.random_walk.psd'"), std::string::npos) << m;
  EXPECT_NE(m.find("one_sided or two_sided"), std::string::npos) << m;

  const std::string missing = error_of(
      "name: x\nsensor: gyroscope\nterms:\n  random_walk:\n"
      "    value: 0.001\n    unit: deg/s/sqrt(Hz)\n");
  EXPECT_NE(missing.find("bad.yaml:6"), std::string::npos) << missing;
  EXPECT_NE(missing.find("'terms.random_walk.psd'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("add psd: two_sided"), std::string::npos) << missing;

  const std::string misplaced = error_of(
      "name: x\nsensor: gyroscope\nterms:\n  random_walk:\n"
      "    value: 0.05\n    unit: deg/sqrt(h)\n    psd: one_sided\n");
  EXPECT_NE(misplaced.find("bad.yaml:7"), std::string::npos) << misplaced;
  EXPECT_NE(misplaced.find("remove the psd key"), std::string::npos) << misplaced;
}

TEST(SpecFileErrors, UnknownKeysAndSensor) {
  const std::string m =
      error_of("name: x\nsensor: gyroscope\nterms:\n  arw: {value: 1, unit: deg/sqrt(h)}\n");
  EXPECT_NE(m.find("bad.yaml:4"), std::string::npos) << m;
  EXPECT_NE(m.find("'terms.arw'"), std::string::npos) << m;
  EXPECT_NE(m.find("random_walk"), std::string::npos) << m;

  const std::string s =
      error_of("name: x\nsensor: gyro\nterms:\n  bias_instability: {value: 2, unit: deg/h}\n");
  EXPECT_NE(s.find("bad.yaml:2"), std::string::npos) << s;
  EXPECT_NE(s.find("gyroscope or accelerometer"), std::string::npos) << s;
}

TEST(SpecFileErrors, DuplicateKey) {
  const std::string m = error_of(
      "name: x\nsensor: gyroscope\nterms:\n"
      "  bias_instability: {value: 2, unit: deg/h}\n"
      "  bias_instability: {value: 3, unit: deg/h}\n");
  EXPECT_NE(m.find("bad.yaml:5"), std::string::npos) << m;
  EXPECT_NE(m.find("'terms.bias_instability': given twice"), std::string::npos) << m;
}

TEST(SpecFileErrors, MalformedYamlGivesLineAndColumn) {
  const std::string m =
      error_of("name: x\nsensor: gyroscope\nterms:\n  random_walk: {value: 1, unit: deg\n");
  EXPECT_NE(m.find("bad.yaml:"), std::string::npos) << m;
  EXPECT_NE(m.find("malformed YAML"), std::string::npos) << m;
  EXPECT_NE(m.find("fix:"), std::string::npos) << m;

  const std::string empty = error_of("");
  EXPECT_NE(empty.find("empty"), std::string::npos) << empty;
  const std::string list = error_of("- a\n- b\n");
  EXPECT_NE(list.find("mapping"), std::string::npos) << list;
}

TEST(SpecFileErrors, MissingFileAndFileContextInMessages) {
  EXPECT_THROW((void)load_spec_file("/nonexistent/spec.yaml"), InputError);
  const auto path = std::filesystem::temp_directory_path() / "imunoise_test_bad_spec.yaml";
  {
    std::ofstream out(path);
    out << "name: x\nsensor: gyroscope\nterms:\n  bias_instability: {value: 2, unit: furlongs}\n";
  }
  try {
    (void)load_spec_file(path.string());
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path.string() + ":4"), std::string::npos) << m;
    EXPECT_NE(m.find("furlongs"), std::string::npos) << m;
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace imunoise
