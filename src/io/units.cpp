#include "imunoise/units.hpp"

#include <array>
#include <string>

#include "imunoise/error.hpp"

namespace imunoise {
namespace {

struct UnitEntry {
  std::string_view name;
  Quantity quantity;
  double to_si;
  // Unused slots are default-constructed (null data), which tells them apart from the real
  // empty-string alias of "1".
  std::array<std::string_view, 3> aliases;
};

bool is_alias(std::string_view alias) { return alias.data() != nullptr; }

constexpr double deg = units::deg_to_rad;
constexpr double g0 = units::g_to_m_per_s2;

// One table is the single source of truth for parsing, listing and error messages.
// "" is an alias of "1" so that an empty --units means fractional frequency.
constexpr std::array<UnitEntry, 28> unit_table{{
    {"rad/s", Quantity::angular_rate, 1.0, {}},
    {"deg/s", Quantity::angular_rate, deg, {"dps", "°/s"}},
    {"deg/h", Quantity::angular_rate, deg / 3600.0, {"deg/hr", "dph", "°/h"}},
    {"rad/h", Quantity::angular_rate, 1.0 / 3600.0, {}},
    {"mrad/s", Quantity::angular_rate, 1e-3, {}},
    {"mdeg/s", Quantity::angular_rate, deg * 1e-3, {}},
    {"arcsec/s", Quantity::angular_rate, units::arcsec_to_rad, {}},
    {"deg/min", Quantity::angular_rate, deg / 60.0, {}},
    {"rpm", Quantity::angular_rate, 2.0 * std::numbers::pi / 60.0, {}},
    {"rad", Quantity::angle, 1.0, {}},
    {"deg", Quantity::angle, deg, {"°"}},
    {"mrad", Quantity::angle, 1e-3, {}},
    {"arcsec", Quantity::angle, units::arcsec_to_rad, {}},
    {"arcmin", Quantity::angle, units::arcmin_to_rad, {}},
    {"m/s^2", Quantity::acceleration, 1.0, {"m/s2"}},
    {"g", Quantity::acceleration, g0, {}},
    {"mg", Quantity::acceleration, g0 * 1e-3, {}},
    {"ug", Quantity::acceleration, g0 * 1e-6, {"µg", "μg"}},  // micro sign and Greek mu
    {"ft/s^2", Quantity::acceleration, units::ft_to_m, {"ft/s2"}},
    {"m/s", Quantity::velocity, 1.0, {}},
    {"ft/s", Quantity::velocity, units::ft_to_m, {}},
    {"1", Quantity::dimensionless, 1.0, {"", "ff"}},
    {"s", Quantity::time, 1.0, {}},
    {"ms", Quantity::time, 1e-3, {}},
    {"us", Quantity::time, 1e-6, {"µs", "μs"}},
    {"ns", Quantity::time, 1e-9, {}},
    {"V", Quantity::voltage, 1.0, {}},
    {"mV", Quantity::voltage, 1e-3, {}},
}};

// Spellings produced by integral_unit for rates without "/s", accepted back so that names
// round-trip, but not advertised in listings.
constexpr std::array<UnitEntry, 5> derived_table{{
    {"deg/h*s", Quantity::angle, deg / 3600.0, {}},
    {"rad/h*s", Quantity::angle, 1.0 / 3600.0, {}},
    {"deg/min*s", Quantity::angle, deg / 60.0, {}},
    {"rpm*s", Quantity::angle, 2.0 * std::numbers::pi / 60.0, {}},
    {"g*s", Quantity::velocity, g0, {}},
}};

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

bool ends_with(std::string_view text, std::string_view suffix) {
  return text.size() >= suffix.size() && text.substr(text.size() - suffix.size()) == suffix;
}

std::string strip_suffix(std::string_view text, std::size_t n) {
  return std::string(text.substr(0, text.size() - n));
}

template <std::size_t N>
const UnitEntry* find_entry(const std::array<UnitEntry, N>& table, std::string_view wanted) {
  for (const auto& entry : table) {
    if (entry.name == wanted) return &entry;
    for (auto alias : entry.aliases) {
      if (is_alias(alias) && alias == wanted) return &entry;
    }
  }
  return nullptr;
}

std::string known_units_text() {
  std::string text;
  for (const auto& entry : unit_table) {
    if (!text.empty()) text += ", ";
    text += entry.name;
    std::string aliases;
    for (auto alias : entry.aliases) {
      if (!is_alias(alias)) continue;
      if (!aliases.empty()) aliases += ", ";
      aliases += alias.empty() ? std::string_view("\"\"") : alias;
    }
    if (!aliases.empty()) text += " (" + aliases + ")";
  }
  return text;
}

}  // namespace

Unit parse_unit(std::string_view name) {
  const std::string_view wanted = trim(name);
  const UnitEntry* entry = find_entry(unit_table, wanted);
  if (entry == nullptr) entry = find_entry(derived_table, wanted);
  if (entry != nullptr) return Unit{std::string(entry->name), entry->quantity, entry->to_si};
  throw InputError("unknown unit '" + std::string(name) + "'; known units: " + known_units_text() +
                   "; fix: pass one of these (names are case-sensitive)");
}

std::vector<std::string> known_unit_names() {
  std::vector<std::string> names;
  for (const auto& entry : unit_table) names.emplace_back(entry.name);
  return names;
}

std::string_view quantity_name(Quantity quantity) {
  switch (quantity) {
    case Quantity::angular_rate: return "angular rate";
    case Quantity::angle: return "angle";
    case Quantity::acceleration: return "acceleration";
    case Quantity::velocity: return "velocity";
    case Quantity::dimensionless: return "dimensionless";
    case Quantity::time: return "time";
    case Quantity::voltage: return "voltage";
  }
  return "unknown";
}

std::string_view si_unit_name(Quantity quantity) {
  switch (quantity) {
    case Quantity::angular_rate: return "rad/s";
    case Quantity::angle: return "rad";
    case Quantity::acceleration: return "m/s^2";
    case Quantity::velocity: return "m/s";
    case Quantity::dimensionless: return "1";
    case Quantity::time: return "s";
    case Quantity::voltage: return "V";
  }
  return "?";
}

Unit integral_unit(const Unit& rate_unit) {
  // Integrating over seconds multiplies by an SI unit, so to_si never changes; only the name
  // and the quantity do.
  Quantity quantity{};
  switch (rate_unit.quantity) {
    case Quantity::angular_rate: quantity = Quantity::angle; break;
    case Quantity::acceleration: quantity = Quantity::velocity; break;
    case Quantity::dimensionless: quantity = Quantity::time; break;
    default:
      throw InputError("unit '" + rate_unit.name + "' measures " +
                       std::string(quantity_name(rate_unit.quantity)) +
                       ", not a rate, so it has no integral here; fix: give the samples' unit as "
                       "an angular rate, an acceleration or 1 (fractional frequency)");
  }
  std::string name;
  const std::string_view n = rate_unit.name;
  if (rate_unit.quantity == Quantity::dimensionless) {
    name = n == "1" ? "s" : (ends_with(n, "/s") ? strip_suffix(n, 2) : std::string(n) + "*s");
  } else if (ends_with(n, "/s^2")) {
    name = strip_suffix(n, 2);
  } else if (ends_with(n, "/s")) {
    name = strip_suffix(n, 2);
  } else {
    name = std::string(n) + "*s";
  }
  return Unit{name, quantity, rate_unit.to_si};
}

Unit derivative_unit(const Unit& angle_unit) {
  Quantity quantity{};
  switch (angle_unit.quantity) {
    case Quantity::angle: quantity = Quantity::angular_rate; break;
    case Quantity::velocity: quantity = Quantity::acceleration; break;
    case Quantity::time: quantity = Quantity::dimensionless; break;
    default:
      throw InputError("unit '" + angle_unit.name + "' measures " +
                       std::string(quantity_name(angle_unit.quantity)) +
                       ", not an angle, velocity or time error, so it has no rate here; fix: "
                       "give the samples' unit as an angle, a velocity or s (time error)");
  }
  std::string name;
  const std::string_view n = angle_unit.name;
  if (ends_with(n, "*s")) {
    name = strip_suffix(n, 2);
  } else if (n == "s") {
    name = "1";
  } else if (angle_unit.quantity == Quantity::velocity && ends_with(n, "/s")) {
    name = std::string(n) + "^2";
  } else {
    name = std::string(n) + "/s";
  }
  return Unit{name, quantity, angle_unit.to_si};
}

}  // namespace imunoise
