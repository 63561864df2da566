#include "imunoise/estimator.hpp"

#include <algorithm>
#include <array>
#include <string>

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
  std::vector<Estimator> list;
  while (true) {
    const auto comma = names.find(',');
    const auto item = names.substr(0, comma);
    const Estimator estimator = parse_estimator(item);
    if (std::find(list.begin(), list.end(), estimator) != list.end()) {
      throw InputError("estimator '" + std::string(item) + "' is listed twice");
    }
    list.push_back(estimator);
    if (comma == std::string_view::npos) break;
    names.remove_prefix(comma + 1);
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
  }
  return 0;
}

}  // namespace imunoise
