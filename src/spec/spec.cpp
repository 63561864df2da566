#include "imunoise/spec/spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <span>
#include <sstream>
#include <system_error>

#include "imunoise/error.hpp"

namespace imunoise {

std::string_view sensor_kind_name(SensorKind kind) {
  return kind == SensorKind::gyroscope ? "gyroscope" : "accelerometer";
}

std::string_view psd_convention_name(PsdConvention convention) {
  switch (convention) {
    case PsdConvention::one_sided:
      return "one_sided";
    case PsdConvention::two_sided:
      return "two_sided";
    case PsdConvention::not_applicable:
      break;
  }
  return "not_applicable";
}

Quantity sensor_quantity(SensorKind kind) {
  return kind == SensorKind::gyroscope ? Quantity::angular_rate : Quantity::acceleration;
}

namespace {

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

// The root of time in a unit's denominator.
enum class RootTime { none, sqrt_h, sqrt_s, sqrt_hz };

struct SplitUnit {
  std::string_view base;  // numerator, e.g. "deg" in "deg/sqrt(h)"
  RootTime root = RootTime::none;
};

SplitUnit split_root(std::string_view unit) {
  struct Suffix {
    std::string_view text;
    RootTime root;
  };
  static constexpr Suffix suffixes[] = {
      {"/sqrt(h)", RootTime::sqrt_h}, {"/sqrt(hr)", RootTime::sqrt_h},
      {"/√h", RootTime::sqrt_h},      {"/sqrt(s)", RootTime::sqrt_s},
      {"/√s", RootTime::sqrt_s},      {"/sqrt(Hz)", RootTime::sqrt_hz},
      {"/√Hz", RootTime::sqrt_hz},    {"/rtHz", RootTime::sqrt_hz},
      {"/rt(Hz)", RootTime::sqrt_hz},
  };
  unit = trim(unit);
  for (const auto& suffix : suffixes) {
    if (unit.size() > suffix.text.size() && unit.ends_with(suffix.text)) {
      return {trim(unit.substr(0, unit.size() - suffix.text.size())), suffix.root};
    }
  }
  return {unit, RootTime::none};
}

std::optional<Unit> try_parse_unit(std::string_view name) {
  try {
    return parse_unit(name);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// The accepted spellings, for messages.
std::string accepted_units(char symbol, SensorKind sensor) {
  const bool gyro = sensor == SensorKind::gyroscope;
  switch (symbol) {
    case 'N':
      return gyro ? "deg/sqrt(h), deg/sqrt(s), rad/sqrt(s) (any angle unit over sqrt(h) or "
                    "sqrt(s)), or a noise density deg/s/sqrt(Hz), deg/h/sqrt(Hz), rad/s/sqrt(Hz) "
                    "(any angular-rate unit over sqrt(Hz), with psd: one_sided|two_sided)"
                  : "m/s/sqrt(h), m/s/sqrt(s) (any velocity unit over sqrt(h) or sqrt(s)), or a "
                    "noise density ug/sqrt(Hz), mg/sqrt(Hz), m/s^2/sqrt(Hz) (any acceleration "
                    "unit over sqrt(Hz), with psd: one_sided|two_sided)";
    case 'B':
      return gyro ? "deg/h, deg/s, rad/s (any angular-rate unit)"
                  : "ug, mg, m/s^2 (any acceleration unit)";
    default:
      return gyro ? "deg/h/sqrt(h), deg/s/sqrt(s), rad/s/sqrt(s) (any angular-rate unit over "
                    "sqrt(h) or sqrt(s)), or rad/s^2/sqrt(Hz), deg/s^2/sqrt(Hz) (with psd)"
                  : "m/s^2/sqrt(h), ug/sqrt(h), mg/sqrt(s) (any acceleration unit over sqrt(h) "
                    "or sqrt(s)), or m/s^3/sqrt(Hz) (with psd)";
  }
}

[[noreturn]] void bad_unit(char symbol, SensorKind sensor, std::string_view unit,
                           std::string_view why) {
  throw InputError("unit '" + std::string(unit) + "' " + std::string(why) + " for " + symbol +
                   " of a " + std::string(sensor_kind_name(sensor)) + "; fix: use one of " +
                   accepted_units(symbol, sensor));
}

// The rate unit of a "rate per second" numerator (K as a density): "rad/s^2" -> rad/s,
// "deg/s/s" -> deg/s, "m/s^3" -> m/s^2, "mg/s" -> mg.
std::optional<Unit> rate_per_second(std::string_view base) {
  if (base == "rad/s^2" || base == "rad/s2") return parse_unit("rad/s");
  if (base == "deg/s^2" || base == "deg/s2") return parse_unit("deg/s");
  if (base == "m/s^3" || base == "m/s3") return parse_unit("m/s^2");
  if (base.size() > 2 && base.ends_with("/s"))
    return try_parse_unit(base.substr(0, base.size() - 2));
  return std::nullopt;
}

}  // namespace

bool is_noise_density_unit(std::string_view unit) {
  return split_root(unit).root == RootTime::sqrt_hz;
}

double spec_term_to_si(char symbol, SensorKind sensor, std::string_view unit_text,
                       PsdConvention convention) {
  const Quantity rate = sensor_quantity(sensor);
  const Quantity integral = sensor == SensorKind::gyroscope ? Quantity::angle : Quantity::velocity;
  const SplitUnit split = split_root(unit_text);
  const double root_time_s = split.root == RootTime::sqrt_h ? units::sqrt_h_to_sqrt_s : 1.0;
  const bool density = split.root == RootTime::sqrt_hz;
  if (density && convention == PsdConvention::not_applicable) {
    throw InputError("noise density '" + std::string(unit_text) +
                     "' needs its PSD convention; fix: add psd: two_sided (density = sqrt of the "
                     "two-sided PSD = N, as IEEE 952 and Kalibr) or psd: one_sided (density = "
                     "sqrt(2) N), as the datasheet states");
  }
  if (!density && convention != PsdConvention::not_applicable) {
    throw InputError("psd: " + std::string(psd_convention_name(convention)) +
                     " applies only to a noise density per sqrt(Hz), not to '" +
                     std::string(unit_text) + "' (an Allan coefficient); fix: remove the psd key");
  }
  const double convention_factor =
      convention == PsdConvention::one_sided ? 1.0 / std::numbers::sqrt2 : 1.0;

  switch (symbol) {
    case 'N': {
      if (split.root == RootTime::none) bad_unit(symbol, sensor, unit_text, "is not a random walk");
      const auto base = try_parse_unit(split.base);
      if (!base) bad_unit(symbol, sensor, unit_text, "has an unknown numerator");
      if (density) {
        if (base->quantity != rate) bad_unit(symbol, sensor, unit_text, "is of the wrong quantity");
        return base->to_si * convention_factor;  // rate/sqrt(Hz) = rate*sqrt(s)
      }
      if (base->quantity != integral)
        bad_unit(symbol, sensor, unit_text, "is of the wrong quantity");
      return base->to_si / root_time_s;
    }
    case 'B': {
      if (split.root != RootTime::none) bad_unit(symbol, sensor, unit_text, "is not a rate");
      const auto base = try_parse_unit(split.base);
      if (!base) bad_unit(symbol, sensor, unit_text, "is unknown");
      if (base->quantity != rate) bad_unit(symbol, sensor, unit_text, "is of the wrong quantity");
      return base->to_si;
    }
    case 'K': {
      if (split.root == RootTime::none) bad_unit(symbol, sensor, unit_text, "is not a random walk");
      if (density) {
        const auto base = rate_per_second(split.base);
        if (!base || base->quantity != rate) {
          bad_unit(symbol, sensor, unit_text, "is not a rate per second per sqrt(Hz)");
        }
        return base->to_si * convention_factor;  // rate/s/sqrt(Hz) = rate/sqrt(s)
      }
      const auto base = try_parse_unit(split.base);
      if (!base) bad_unit(symbol, sensor, unit_text, "has an unknown numerator");
      if (base->quantity != rate) bad_unit(symbol, sensor, unit_text, "is of the wrong quantity");
      return base->to_si / root_time_s;
    }
    default:
      break;
  }
  throw InputError(std::string("unknown noise term '") + symbol + "'; fix: use N, B or K");
}

// ---------------------------------------------------------------------------------------------
// YAML loading

namespace {

constexpr std::string_view kTermKeys[] = {"random_walk", "bias_instability", "rate_random_walk"};
constexpr std::string_view kTopKeys[] = {"name",  "sensor", "description", "tolerance",
                                         "terms", "range",  "bandwidth",   "scale_factor"};

std::string join(std::span<const std::string_view> items) {
  std::string out;
  for (const auto item : items) {
    if (!out.empty()) out += ", ";
    out += item;
  }
  return out;
}

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& what,
                         const std::string& fix) const {
    std::string where = source_;
    if (node.IsDefined() && node.Mark().line >= 0) {
      where += ":" + std::to_string(node.Mark().line + 1);
    }
    throw InputError(where + ": key '" + key + "': " + what + "; fix: " + fix);
  }

  void check_keys(const YAML::Node& map, const std::string& path,
                  std::span<const std::string_view> known) const {
    std::vector<std::string> seen;
    for (const auto& entry : map) {
      const auto key = entry.first.as<std::string>();
      const std::string full = path.empty() ? key : path + "." + key;
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        fail(entry.first, full, "unknown key",
             "use one of " + join(known) + " (keys are case-sensitive)");
      }
      // yaml-cpp keeps duplicates silently; a datasheet with two values for one key is a typo.
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
        fail(entry.first, full, "given twice", "keep one of the two entries");
      }
      seen.push_back(key);
    }
  }

  YAML::Node require_map(const YAML::Node& parent, const std::string& key, const std::string& path,
                         const std::string& example) const {
    const YAML::Node node = parent[key];
    if (!node) fail(parent, path, "missing", "add it, e.g. " + example);
    if (!node.IsMap()) fail(node, path, "must be a mapping", "write it as " + example);
    return node;
  }

  std::string string_value(const YAML::Node& node, const std::string& path,
                           const std::string& example) const {
    if (!node.IsScalar()) fail(node, path, "must be a text value", "write e.g. " + example);
    return node.as<std::string>();
  }

  double number(const YAML::Node& node, const std::string& path, bool allow_zero) const {
    if (!node.IsScalar()) fail(node, path, "must be a number", "write a plain number, e.g. 0.05");
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(node, path, "'" + node.as<std::string>() + "' is not a number",
           "write a plain number without unit (the unit goes in the 'unit' key)");
    }
    if (!std::isfinite(value)) fail(node, path, "must be finite", "write a finite number");
    if (value < 0.0 || (!allow_zero && value == 0.0)) {
      fail(node, path,
           "must be " + std::string(allow_zero ? "zero or positive" : "positive") + " (got " +
               node.as<std::string>() + ")",
           path == "range.value" ? "give the half-width of the symmetric range, e.g. 100 for +/-100"
           : path.ends_with("tolerance") ? "give a relative tolerance >= 0, e.g. 0.1 for 10 %"
                                         : "give the datasheet value as a positive magnitude");
    }
    return value;
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

PsdConvention parse_convention(const Reader& reader, const YAML::Node& node,
                               const std::string& path) {
  const auto text = reader.string_value(node, path, "two_sided");
  if (text == "one_sided") return PsdConvention::one_sided;
  if (text == "two_sided") return PsdConvention::two_sided;
  reader.fail(node, path, "unknown PSD convention '" + text + "'",
              "use one_sided or two_sided, as the datasheet states");
}

SpecTerm parse_term(const Reader& reader, const YAML::Node& node, const std::string& path,
                    char symbol, SensorKind sensor, double default_tolerance) {
  static constexpr std::string_view keys[] = {"value", "unit", "psd", "tolerance"};
  if (!node.IsMap()) {
    reader.fail(node, path, "must be a mapping", "write it as {value: 0.05, unit: deg/sqrt(h)}");
  }
  reader.check_keys(node, path, keys);
  SpecTerm term;
  if (!node["value"]) reader.fail(node, path + ".value", "missing", "add value: <number>");
  if (!node["unit"]) {
    reader.fail(node, path + ".unit", "missing",
                "add unit: <unit>, one of " + accepted_units(symbol, sensor));
  }
  term.value = reader.number(node["value"], path + ".value", false);
  term.unit = reader.string_value(node["unit"], path + ".unit", "deg/sqrt(h)");
  if (node["psd"]) term.psd = parse_convention(reader, node["psd"], path + ".psd");
  term.tolerance = node["tolerance"] ? reader.number(node["tolerance"], path + ".tolerance", true)
                                     : default_tolerance;
  try {
    term.to_si = spec_term_to_si(symbol, sensor, term.unit, term.psd);
  } catch (const InputError& e) {
    const std::string message = e.what();
    const auto fix = message.find("; fix: ");
    const bool about_psd =
        message.find("PSD convention") != std::string::npos || message.rfind("psd:", 0) == 0;
    const YAML::Node at = about_psd && node["psd"] ? node["psd"] : node["unit"];
    reader.fail(at, path + (about_psd ? ".psd" : ".unit"), message.substr(0, fix),
                fix == std::string::npos ? "see docs/spec.md" : message.substr(fix + 7));
  }
  term.value_si = term.value * term.to_si;
  return term;
}

SpecRating parse_rating(const Reader& reader, const YAML::Node& node, const std::string& path,
                        SensorKind sensor) {
  static constexpr std::string_view keys[] = {"value", "unit"};
  const std::string example = path == "range"       ? "{value: 100, unit: deg/s}"
                              : path == "bandwidth" ? "{value: 50, unit: Hz}"
                                                    : "{value: 20, unit: mV/(deg/s)}";
  if (!node.IsMap()) reader.fail(node, path, "must be a mapping", "write it as " + example);
  reader.check_keys(node, path, keys);
  if (!node["value"]) reader.fail(node, path + ".value", "missing", "add it: " + example);
  if (!node["unit"]) reader.fail(node, path + ".unit", "missing", "add it: " + example);
  SpecRating rating;
  rating.value = reader.number(node["value"], path + ".value", false);
  rating.unit = reader.string_value(node["unit"], path + ".unit", example);
  const Quantity rate = sensor_quantity(sensor);
  const std::string rate_examples =
      sensor == SensorKind::gyroscope ? "deg/s, rad/s, deg/h" : "g, mg, m/s^2";
  const auto unit_node = node["unit"];
  if (path == "range") {
    const auto unit = try_parse_unit(rating.unit);
    if (!unit || unit->quantity != rate) {
      reader.fail(unit_node, path + ".unit",
                  "'" + rating.unit + "' is not a unit of " + std::string(quantity_name(rate)),
                  "use one of " + rate_examples);
    }
    rating.value_si = rating.value * unit->to_si;
  } else if (path == "bandwidth") {
    double factor = 0.0;
    if (rating.unit == "Hz") factor = 1.0;
    if (rating.unit == "kHz") factor = 1e3;
    if (factor == 0.0)
      reader.fail(unit_node, path + ".unit", "unknown unit '" + rating.unit + "'", "use Hz or kHz");
    rating.value_si = rating.value * factor;
  } else {
    // "<voltage>/(<rate>)" or "<voltage>/<rate>"
    const std::string_view text = trim(rating.unit);
    const auto slash = text.find('/');
    std::optional<Unit> voltage;
    std::optional<Unit> per;
    if (slash != std::string_view::npos) {
      voltage = try_parse_unit(text.substr(0, slash));
      auto denominator = trim(text.substr(slash + 1));
      if (denominator.size() > 2 && denominator.front() == '(' && denominator.back() == ')') {
        denominator = denominator.substr(1, denominator.size() - 2);
      }
      per = try_parse_unit(denominator);
    }
    if (!voltage || voltage->quantity != Quantity::voltage || !per || per->quantity != rate) {
      reader.fail(
          unit_node, path + ".unit",
          "'" + rating.unit + "' is not a voltage per " + std::string(quantity_name(rate)),
          std::string("write e.g. ") + (sensor == SensorKind::gyroscope ? "mV/(deg/s)" : "mV/g"));
    }
    rating.value_si = rating.value * voltage->to_si / per->to_si;
  }
  return rating;
}

Spec parse_document(const Reader& reader, const YAML::Node& root) {
  if (!root.IsMap()) {
    reader.fail(root, "(document)", "a spec file is a YAML mapping",
                "start with 'name: ...', 'sensor: gyroscope' and 'terms:' (see docs/spec.md)");
  }
  reader.check_keys(root, "", kTopKeys);
  Spec spec;
  spec.source = reader.source();
  if (!root["name"])
    reader.fail(root, "name", "missing", "add name: <short name>, e.g. name: tg100");
  spec.name = reader.string_value(root["name"], "name", "tg100");
  if (spec.name.empty()) reader.fail(root["name"], "name", "is empty", "give a short name");
  if (!root["sensor"]) {
    reader.fail(root, "sensor", "missing", "add sensor: gyroscope or sensor: accelerometer");
  }
  const auto sensor = reader.string_value(root["sensor"], "sensor", "gyroscope");
  if (sensor == "gyroscope") {
    spec.sensor = SensorKind::gyroscope;
  } else if (sensor == "accelerometer") {
    spec.sensor = SensorKind::accelerometer;
  } else {
    reader.fail(root["sensor"], "sensor", "unknown sensor kind '" + sensor + "'",
                "use gyroscope or accelerometer");
  }
  if (root["description"]) {
    spec.description = reader.string_value(root["description"], "description", "\"TG-100\"");
  }
  if (root["tolerance"]) spec.tolerance = reader.number(root["tolerance"], "tolerance", true);

  const auto terms = reader.require_map(root, "terms", "terms",
                                        "terms: {random_walk: {value: 0.05, unit: deg/sqrt(h)}}");
  reader.check_keys(terms, "terms", kTermKeys);
  if (terms.size() == 0) {
    reader.fail(terms, "terms", "no noise term given", "give at least one of " + join(kTermKeys));
  }
  if (terms["random_walk"]) {
    spec.random_walk = parse_term(reader, terms["random_walk"], "terms.random_walk", 'N',
                                  spec.sensor, spec.tolerance);
  }
  if (terms["bias_instability"]) {
    spec.bias_instability = parse_term(reader, terms["bias_instability"], "terms.bias_instability",
                                       'B', spec.sensor, spec.tolerance);
  }
  if (terms["rate_random_walk"]) {
    spec.rate_random_walk = parse_term(reader, terms["rate_random_walk"], "terms.rate_random_walk",
                                       'K', spec.sensor, spec.tolerance);
  }
  if (root["range"]) spec.range = parse_rating(reader, root["range"], "range", spec.sensor);
  if (root["bandwidth"]) {
    spec.bandwidth = parse_rating(reader, root["bandwidth"], "bandwidth", spec.sensor);
  }
  if (root["scale_factor"]) {
    spec.scale_factor = parse_rating(reader, root["scale_factor"], "scale_factor", spec.sensor);
  }
  return spec;
}

}  // namespace

Spec parse_spec_yaml(std::string_view yaml_text, const std::string& source) {
  const Reader reader(source);
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::ParserException& e) {
    throw InputError(source + ":" + std::to_string(e.mark.line + 1) + ":" +
                     std::to_string(e.mark.column + 1) + ": malformed YAML (" + e.msg +
                     "); fix: correct the syntax there (indent with spaces, 'key: value', "
                     "see docs/spec.md)");
  }
  if (!root || root.IsNull()) {
    throw InputError(source +
                     ": the spec file is empty; fix: write name, sensor and terms "
                     "(see docs/spec.md and examples/specs/tg100.yaml)");
  }
  try {
    return parse_document(reader, root);
  } catch (const YAML::Exception& e) {
    // Conversions are checked above; anything left is a structural surprise.
    throw InputError(source + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg +
                     "; fix: see docs/spec.md for the layout");
  }
}

Spec load_spec_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path + ": is a directory; fix: give the path of a YAML spec file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(path +
                     ": cannot open the spec file; fix: check the path, or use a built-in "
                     "spec name (tg100)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_spec_yaml(text.str(), path);
}

// ---------------------------------------------------------------------------------------------
// Built-in specs

namespace {

SpecTerm builtin_term(char symbol, double value, std::string unit) {
  SpecTerm term;
  term.value = value;
  term.unit = std::move(unit);
  term.to_si = spec_term_to_si(symbol, SensorKind::gyroscope, term.unit, term.psd);
  term.value_si = term.value * term.to_si;
  return term;
}

// A datasheet gyroscope at +25 degC: white-noise and bias-instability terms, range, bandwidth.
Spec builtin_gyro(std::string name, std::string description, SpecTerm random_walk,
                  SpecTerm bias_instability, double range_deg_s, double bandwidth_hz) {
  Spec spec;
  spec.source = "builtin:" + name;
  spec.name = std::move(name);
  spec.description = std::move(description);
  spec.sensor = SensorKind::gyroscope;
  spec.tolerance = 0.0;
  spec.random_walk = std::move(random_walk);
  spec.bias_instability = std::move(bias_instability);
  spec.range = SpecRating{range_deg_s, "deg/s", range_deg_s * units::deg_to_rad};
  spec.bandwidth = SpecRating{bandwidth_hz, "Hz", bandwidth_hz};
  return spec;
}

Spec tg100() {
  // Paper Table 1 (TG-100 datasheet, "Laboratory of Micro-Devices"), values at +25 degC.
  Spec spec = builtin_gyro("tg100",
                           "TG-100 MEMS angular-rate sensor (Laboratory of Micro-Devices), "
                           "datasheet as in the paper's Table 1, +25 degC",
                           builtin_term('N', 0.05, "deg/sqrt(h)"), builtin_term('B', 2.0, "deg/h"),
                           100.0, 50.0);
  spec.scale_factor = SpecRating{20.0, "mV/(deg/s)", 20.0e-3 / units::deg_to_rad};
  return spec;
}

Spec adis16405() {
  // Analog Devices ADIS16405 (triaxial inertial sensor with magnetometer), datasheet rev. B,
  // gyroscope specifications at +25 degC: angle random walk 2.0 deg/sqrt(h), in-run bias
  // stability 0.007 deg/s (1 sigma, from the Allan curve), dynamic range +/-300 deg/s,
  // bandwidth 330 Hz. The output is digital (0.05 deg/s per LSB at +/-300 deg/s): there is no
  // analog scale factor.
  return builtin_gyro("adis16405",
                      "ADIS16405 MEMS IMU gyroscopes (Analog Devices), datasheet at +25 degC; "
                      "digital output, 0.05 deg/s LSB",
                      builtin_term('N', 2.0, "deg/sqrt(h)"), builtin_term('B', 0.007, "deg/s"),
                      300.0, 330.0);
}

}  // namespace

std::vector<std::string> builtin_spec_names() { return {"adis16405", "tg100"}; }

Spec builtin_spec(std::string_view name) {
  if (name == "tg100") return tg100();
  if (name == "adis16405") return adis16405();
  std::string known;
  for (const auto& n : builtin_spec_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown built-in spec '" + std::string(name) + "'; fix: use one of " + known +
                   " or the path of a YAML spec file (docs/spec.md)");
}

Spec resolve_spec(const std::string& name_or_path) {
  for (const auto& name : builtin_spec_names()) {
    if (name == name_or_path) return builtin_spec(name);
  }
  std::error_code ec;
  if (std::filesystem::exists(name_or_path, ec)) return load_spec_file(name_or_path);
  std::string names;
  for (const auto& name : builtin_spec_names()) names += (names.empty() ? "" : ", ") + name;
  throw InputError("--spec '" + name_or_path + "': neither a built-in spec (" + names +
                   ") nor an existing file; fix: pass a built-in name or the path of a YAML spec "
                   "file (format: docs/spec.md, example: examples/specs/tg100.yaml)");
}

}  // namespace imunoise
