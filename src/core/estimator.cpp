#include "imunoise/estimator.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "imunoise/comma_list.hpp"
#include "imunoise/error.hpp"

namespace imunoise {
namespace {

struct EstimatorInfo {
  Estimator estimator;
  std::string_view name;
};

constexpr std::array kEstimators{
    EstimatorInfo{Estimator::adev, "adev"},   EstimatorInfo{Estimator::oadev, "oadev"},
    EstimatorInfo{Estimator::mdev, "mdev"},   EstimatorInfo{Estimator::tdev, "tdev"},
    EstimatorInfo{Estimator::hdev, "hdev"},   EstimatorInfo{Estimator::ohdev, "ohdev"},
    EstimatorInfo{Estimator::totdev, "totdev"}, EstimatorInfo{Estimator::mtotdev, "mtotdev"},
    EstimatorInfo{Estimator::ttotdev, "ttotdev"}, EstimatorInfo{Estimator::htotdev, "htotdev"},
    EstimatorInfo{Estimator::theo1, "theo1"}, EstimatorInfo{Estimator::theobr, "theobr"},
    EstimatorInfo{Estimator::mtie, "mtie"},
    EstimatorInfo{Estimator::tierms, "tierms"},
};

std::string known_names() {
  std::string names;
  for (const auto& info : kEstimators) {
    if (!names.empty()) names += ", ";
    names += info.name;
  }
  return names;
}

}  // namespace

std::vector<Estimator> all_estimators() {
  std::vector<Estimator> list;
  for (const auto& info : kEstimators) list.push_back(info.estimator);
  return list;
}

std::string_view estimator_name(Estimator estimator) {
  for (const auto& info : kEstimators) {
    if (info.estimator == estimator) return info.name;
  }
  return "unknown";
}

Estimator parse_estimator(std::string_view name) {
  for (const auto& info : kEstimators) {
    if (info.name == name) return info.estimator;
  }
  throw InputError("unknown estimator '" + std::string(name) + "'; known: " + known_names() +
                   " (or all)");
}

std::vector<Estimator> parse_estimator_list(std::string_view names) {
  if (names == "all") return all_estimators();
  const auto items = split_comma_list(names);
  if (items.empty()) throw InputError("no estimator given; known: " + known_names() + " (or all)");
  std::vector<Estimator> list;
  for (const auto& item : items) {
    const Estimator estimator = parse_estimator(item);
    if (std::find(list.begin(), list.end(), estimator) != list.end()) {
      throw InputError("estimator '" + item + "' is listed twice");
    }
    list.push_back(estimator);
  }
  return list;
}

std::size_t term_count(Estimator estimator, std::size_t n_phase, std::size_t m) {
  if (m == 0 || n_phase == 0) return 0;
  const std::size_t last = n_phase - 1;  // index of the last phase point
  switch (estimator) {
    case Estimator::adev:  // x[k], x[k+m], x[k+2m] at k = 0, m, 2m, ...
      return last >= 2 * m ? (last - 2 * m) / m + 1 : 0;
    case Estimator::oadev:
      return last >= 2 * m ? n_phase - 2 * m : 0;
    case Estimator::mdev:
    case Estimator::tdev:  // window sums of m second differences spanning 3m points
      return n_phase >= 3 * m ? n_phase - 3 * m + 1 : 0;
    case Estimator::hdev:
      return last >= 3 * m ? (last - 3 * m) / m + 1 : 0;
    case Estimator::ohdev:
      return last >= 3 * m ? n_phase - 3 * m : 0;
    case Estimator::totdev:  // one term per interior point of the reflected sequence
      return m <= max_averaging_factor(estimator, n_phase) ? n_phase - 2 : 0;
    case Estimator::mtotdev:
    case Estimator::ttotdev:  // one 3m-point phase subsequence per term
      return n_phase >= 3 * m ? n_phase - 3 * m + 1 : 0;
    case Estimator::htotdev:  // one 3m-point frequency subsequence per term; m = 1 is ohdev
      if (m == 1) return n_phase >= 4 ? n_phase - 3 : 0;
      return n_phase >= 3 * m + 1 ? n_phase - 3 * m : 0;
    case Estimator::theo1:  // (N - m) start points times m/2 spans, as Stable32 counts
    case Estimator::theobr:
      return (m % 2 == 0 && m <= max_averaging_factor(estimator, n_phase)) ? (n_phase - m) * (m / 2)
                                                                            : 0;
    case Estimator::mtie:
    case Estimator::tierms:  // windows of m + 1 points
      return m < n_phase ? n_phase - m : 0;
  }
  return 0;
}

std::size_t max_averaging_factor(Estimator estimator, std::size_t n_phase) {
  if (n_phase == 0) return 0;
  switch (estimator) {
    case Estimator::adev:
    case Estimator::oadev:
      return (n_phase - 1) / 2;
    case Estimator::mdev:
    case Estimator::tdev:
      return n_phase / 3;
    case Estimator::hdev:
    case Estimator::ohdev:
      return (n_phase - 1) / 3;
    case Estimator::totdev:
      return n_phase >= 3 ? (n_phase - 1) / 2 : 0;
    case Estimator::mtotdev:
    case Estimator::ttotdev:
      return n_phase / 3;
    case Estimator::htotdev:
      return n_phase >= 4 ? (n_phase - 1) / 3 : 0;
    case Estimator::theo1: {
      const std::size_t m = n_phase - 1;  // largest m with i + m <= N - 1 for i = 0
      return m >= 2 ? m - m % 2 : 0;
    }
    case Estimator::theobr:  // its bias factor needs floor(N/30) - 3 >= 0 (theo.hpp)
      return n_phase >= 90 ? max_averaging_factor(Estimator::theo1, n_phase) : 0;
    case Estimator::mtie:
    case Estimator::tierms:
      return n_phase - 1;
  }
  return 0;
}

bool reports_angle(Estimator estimator) {
  return estimator == Estimator::tdev || estimator == Estimator::ttotdev ||
         estimator == Estimator::mtie || estimator == Estimator::tierms;
}

bool requires_even_factor(Estimator estimator) {
  return estimator == Estimator::theo1 || estimator == Estimator::theobr;
}

double tau_per_factor(Estimator estimator) { return requires_even_factor(estimator) ? 0.75 : 1.0; }

}  // namespace imunoise
