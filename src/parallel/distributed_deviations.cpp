#include "imunoise/parallel/distributed_deviations.hpp"

#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include "imunoise/difference_accumulator.hpp"
#include "imunoise/error.hpp"
#include "imunoise/io/binary_reader.hpp"
#include "imunoise/load/integrate.hpp"
#include "imunoise/phase.hpp"
#include "imunoise/theo.hpp"

namespace imunoise::parallel {
namespace {

constexpr int kSliceTag = 21;

// Every rank passes here together: when any rank failed, all leave (the failed ones with
// their own message, the others saying why they stop) instead of waiting for each other.
void check_together(Ranks& ranks, const std::optional<std::string>& error) {
  if (ranks.all_ok(!error.has_value())) return;
  if (error) throw InputError(*error);
  throw InputError("rank " + std::to_string(ranks.rank()) + " stopped: another rank failed (its message is above)");
}

struct Slice {
  std::size_t first_phase = 0;   ///< global index of the slice's first phase sample
  std::vector<double> phase_si;  ///< in the slice's own coordinates
};

// floor(n rank / size) without overflow: n = q size + r gives q rank + floor(r rank / size).
std::size_t cut(std::size_t n, int rank, int size) {
  const auto r = static_cast<std::size_t>(rank), p = static_cast<std::size_t>(size);
  return (n / p) * r + (n % p) * r / p;
}

Slice read_binary_slice(const load::RecordPlan& plan, const std::string& path, Ranks& ranks,
                        std::size_t& n_phase) {
  std::optional<std::string> error;
  load::BinaryLayout layout;
  try {
    layout = load::binary_layout(plan, path, ranks.rank() == 0);
  } catch (const InputError& e) {
    error = e.what();
  }
  check_together(ranks, error);
  const double offset = ranks.broadcast(layout.rate_offset_si);
  const bool rate = plan.meta.kind == InputKind::rate;
  n_phase = rate ? layout.records + 1 : layout.records;
  Slice slice;
  try {
    // Rate: records [a, b) integrate into phase [a, b]. Angle: phase [a, b] read directly.
    const std::size_t span = rate ? layout.records : layout.records - 1;
    const std::size_t a = cut(span, ranks.rank(), ranks.size());
    const std::size_t b = cut(span, ranks.rank() + 1, ranks.size());
    slice.first_phase = a;
    slice.phase_si = load::read_phase_slice(plan, path, a, rate ? b - a : b - a + 1, offset);
  } catch (const InputError& e) {
    error = e.what();
  }
  check_together(ranks, error);
  return slice;
}

// Text: rank 0 reads everything and sends each rank its slice of the phase.
Slice scatter_text(const load::LoadOptions& input, Ranks& ranks, Record& record,
                   std::size_t& n_phase) {
  std::optional<std::string> error;
  if (ranks.rank() == 0) {
    try {
      record = load::load(input);
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  check_together(ranks, error);
  n_phase = static_cast<std::size_t>(ranks.broadcast(static_cast<double>(record.phase_si.size())));
  record.rate_hz = ranks.broadcast(record.rate_hz);
  Slice slice;
  const std::size_t span = n_phase - 1;
  slice.first_phase = cut(span, ranks.rank(), ranks.size());
  if (ranks.rank() == 0) {
    for (int r = 1; r < ranks.size(); ++r) {
      const std::size_t a = cut(span, r, ranks.size()), b = cut(span, r + 1, ranks.size());
      std::vector<std::uint8_t> bytes((b - a + 1) * sizeof(double));
      std::memcpy(bytes.data(), record.phase_si.data() + a, bytes.size());
      ranks.send(r, kSliceTag, bytes);
    }
    const std::size_t b = cut(span, 1, ranks.size());
    slice.phase_si.assign(record.phase_si.begin(), record.phase_si.begin() + static_cast<std::ptrdiff_t>(b + 1));
    record.phase_si.clear();
    record.phase_si.shrink_to_fit();
  } else {
    const auto bytes = ranks.receive(0, kSliceTag);
    slice.phase_si.resize(bytes.size() / sizeof(double));
    std::memcpy(slice.phase_si.data(), bytes.data(), bytes.size());
  }
  return slice;
}

}  // namespace

bool is_mergeable(Estimator e) {
  return e == Estimator::adev || e == Estimator::oadev || e == Estimator::mdev ||
         e == Estimator::tdev || e == Estimator::hdev || e == Estimator::ohdev;
}

DistributedCurves distributed_deviations(Ranks& ranks, const load::LoadOptions& input,
                                         const std::vector<Estimator>& estimators, const TauGrid& grid) {
  for (const Estimator e : estimators) {
    if (!is_mergeable(e)) {
      throw InputError("--mpi: " + std::string(estimator_name(e)) +
                       " cannot be split into slices and merged; --mpi computes adev, oadev, mdev, "
                       "tdev, hdev and ohdev (drop --mpi for the others)");
    }
  }
  DistributedCurves out;
  out.root = ranks.rank() == 0;
  std::optional<std::string> error;
  load::RecordPlan plan;
  try {
    plan = load::plan_record(input);
    if (input.file == "-") {
      throw InputError("--mpi reads the file on every rank: give a file path, not standard input");
    }
  } catch (const InputError& e) {
    error = e.what();
  }
  check_together(ranks, error);
  out.record = plan.meta;
  Slice slice = plan.binary ? read_binary_slice(plan, input.file, ranks, out.n_phase)
                                  : scatter_text(input, ranks, out.record, out.n_phase);
  if (plan.binary) out.record.n_samples = plan.meta.kind == InputKind::rate ? out.n_phase - 1 : out.n_phase;
  out.record.phase_si.clear();
  const double tau0_s = 1.0 / out.record.rate_hz;

  for (const Estimator estimator : estimators) {
    if (max_averaging_factor(estimator, out.n_phase) == 0) {
      throw InputError(out.record.source + ": " + std::to_string(out.record.n_samples) +
                       " samples are too few for " + std::string(estimator_name(estimator)));
    }
    const auto factors =
        estimator_averaging_factors(estimator, grid, out.record.rate_hz, out.n_phase);
    DifferenceAccumulator acc(estimator, factors, slice.first_phase);
    acc.push(slice.phase_si);
    tree_merge(ranks, [&acc] { return acc.to_bytes(); },
                    [&acc](const std::vector<std::uint8_t>& theirs) {
                      acc.merge(DifferenceAccumulator::from_bytes(theirs));
                    });
    if (out.root) out.curves.push_back(acc.deviations(tau0_s));
  }
  if (out.root) out.root_phase_si = std::move(slice.phase_si);
  return out;
}

}  // namespace imunoise::parallel
