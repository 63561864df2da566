#include "imunoise/fleet/outcome_wire.hpp"

#include <cstring>

#include <fmt/core.h>

#include "imunoise/error.hpp"

namespace imunoise::fleet {
namespace {

class Writer {
 public:
  void u64(std::uint64_t v) { raw(&v, 8); }
  void f64(double v) { raw(&v, 8); }
  void flag(bool v) { bytes.push_back(v ? 1 : 0); }
  void text(const std::string& s) {
    u64(s.size());
    raw(s.data(), s.size());
  }
  std::vector<std::uint8_t> bytes;

 private:
  void raw(const void* p, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(p);
    bytes.insert(bytes.end(), b, b + n);
  }
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::uint64_t u64() {
    std::uint64_t v = 0;
    raw(&v, 8);
    return v;
  }
  double f64() {
    double v = 0;
    raw(&v, 8);
    return v;
  }
  bool flag() {
    std::uint8_t v = 0;
    raw(&v, 1);
    return v != 0;
  }
  std::string text() {
    const std::uint64_t n = u64();
    if (n > bytes_.size() - at_) fail();
    std::string s(reinterpret_cast<const char*>(bytes_.data() + at_), n);
    at_ += n;
    return s;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  [[noreturn]] static void fail() {
    throw InputError("a fleet rank sent a truncated result (an internal error: the ranks run different builds?)");
  }
  void raw(void* p, std::size_t n) {
    if (n > bytes_.size() - at_) fail();
    std::memcpy(p, bytes_.data() + at_, n);
    at_ += n;
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t at_ = 0;
};

void put(Writer& w, const SensorSummary& s) {
  w.f64(s.rate_hz);
  w.u64(s.n_samples);
  w.text(s.unit);
  for (const auto& t : s.terms) {
    w.text(t.name);
    w.text(t.unit);
    w.f64(t.value);
    w.f64(t.ci_low);
    w.f64(t.ci_high);
    w.flag(t.identified);
    w.flag(t.fitted);
  }
  w.flag(s.datasheet.has_value());
  if (s.datasheet) {
    w.text(s.datasheet->spec);
    w.flag(s.datasheet->all_pass);
    w.u64(s.datasheet->terms.size());
    for (const auto& t : s.datasheet->terms) {
      w.text(t.symbol);
      w.text(t.verdict);
      w.f64(t.measured);
      w.text(t.measured_unit);
      w.f64(t.deviation_percent);
      w.f64(t.spec);
      w.text(t.spec_unit);
      w.flag(t.conclusive);
    }
  }
  w.flag(s.nav.has_value());
  if (s.nav) {
    w.f64(s.nav->t_s);
    w.f64(s.nav->latitude_deg);
    w.flag(s.nav->computed);
    w.text(s.nav->error);
    w.u64(s.nav->models.size());
    for (const auto& m : s.nav->models) {
      w.text(m.model);
      w.f64(m.lat_deg);
      w.f64(m.path_m);
      w.f64(m.lon_deg);
    }
  }
}

SensorSummary get_summary(Reader& r) {
  SensorSummary s;
  s.rate_hz = r.f64();
  s.n_samples = r.u64();
  s.unit = r.text();
  for (auto& t : s.terms) {
    t.name = r.text();
    t.unit = r.text();
    t.value = r.f64();
    t.ci_low = r.f64();
    t.ci_high = r.f64();
    t.identified = r.flag();
    t.fitted = r.flag();
  }
  if (r.flag()) {
    DatasheetSummary d;
    d.spec = r.text();
    d.all_pass = r.flag();
    for (std::uint64_t n = r.u64(), k = 0; k < n; ++k) {
      DatasheetTerm t;
      t.symbol = r.text();
      t.verdict = r.text();
      t.measured = r.f64();
      t.measured_unit = r.text();
      t.deviation_percent = r.f64();
      t.spec = r.f64();
      t.spec_unit = r.text();
      t.conclusive = r.flag();
      d.terms.push_back(std::move(t));
    }
    s.datasheet = std::move(d);
  }
  if (r.flag()) {
    study::NavAtHorizon nav;
    nav.t_s = r.f64();
    nav.latitude_deg = r.f64();
    nav.computed = r.flag();
    nav.error = r.text();
    for (std::uint64_t n = r.u64(), k = 0; k < n; ++k) {
      study::NavModelAtHorizon m;
      m.model = r.text();
      m.lat_deg = r.f64();
      m.path_m = r.f64();
      m.lon_deg = r.f64();
      nav.models.push_back(std::move(m));
    }
    s.nav = std::move(nav);
  }
  return s;
}

}  // namespace

std::vector<std::uint8_t> encode_outcome(std::size_t index, const SensorOutcome& outcome) {
  Writer w;
  w.u64(index);
  w.flag(outcome.ok());
  if (outcome.ok()) {
    put(w, *outcome.summary);
    w.text(outcome.document.dump());
  } else {
    w.text(outcome.error);
  }
  return std::move(w.bytes);
}

std::size_t decode_outcome(std::span<const std::uint8_t> bytes, std::span<const std::string> files,
                           SensorOutcome& outcome) {
  Reader r(bytes);
  const std::uint64_t index = r.u64();
  if (index >= files.size()) throw InputError("a fleet rank sent a result for a file it was not given");
  outcome = {};
  outcome.file = files[index];
  if (r.flag()) {
    outcome.summary = get_summary(r);
    outcome.document = nlohmann::json::parse(r.text());
  } else {
    outcome.error = r.text();
    outcome.document = nullptr;
  }
  if (!r.done()) throw InputError("a fleet rank sent a result longer than its content");
  return static_cast<std::size_t>(index);
}

std::string summary_line(const nlohmann::json& fleet) {
  const auto& summary = fleet["summary"];
  std::string pass = "no datasheet (--spec)";
  if (!summary["datasheet"].is_null()) {
    pass = fmt::format("{} of {} pass {} ({:.0f} %)", summary["datasheet"]["n_pass"].get<std::size_t>(),
                       summary["datasheet"]["n_judged"].get<std::size_t>(),
                       summary["datasheet"]["spec"].get<std::string>(),
                       100.0 * summary["datasheet"]["pass_rate"].get<double>());
  }
  return fmt::format("{} files, {} analysed, {} failed; {}; {} outliers", summary["n_files"].get<std::size_t>(),
                     summary["n_analysed"].get<std::size_t>(), summary["n_failed"].get<std::size_t>(), pass,
                     summary["outliers"].size());
}

}  // namespace imunoise::fleet
