#include "difference_sums.hpp"

#include <algorithm>

#include "kernels.hpp"
#include "parallel.hpp"

namespace imunoise::detail {
namespace {

// Start indices are processed in blocks small enough that the few windows one block reads
// for all factors stay in L2 (for octave factors the window at offset 2m is the window at
// offset m of the next factor). Blocks are grouped into super-chunks, the unit of work for a
// thread; each super-chunk writes its own partial sums, which are reduced in a fixed order,
// so results are bitwise identical for any thread count.
constexpr std::size_t kBlock = 4096;
constexpr std::size_t kMinChunk = 16 * kBlock;
constexpr std::size_t kMaxPartials = std::size_t{1} << 23;  // 64 MB of partial sums at most

std::size_t chunk_length(std::size_t n_starts, std::size_t n_factors) {
  std::size_t chunk = kMinChunk;
  while ((n_starts / chunk + 1) * n_factors > kMaxPartials) chunk *= 2;
  return chunk;
}

std::size_t overlapping_count(std::size_t n_phase, int order, std::size_t m) {
  const std::size_t span = static_cast<std::size_t>(order) * m;
  return n_phase > span ? n_phase - span : 0;
}

}  // namespace

DifferenceSums overlapping_difference_sums(std::span<const double> phase, int order,
                                           std::span<const std::size_t> factors, unsigned threads) {
  const std::size_t n_factors = factors.size();
  DifferenceSums result{std::vector<double>(n_factors, 0.0), std::vector<std::size_t>(n_factors)};
  std::size_t max_count = 0;
  for (std::size_t t = 0; t < n_factors; ++t) {
    result.n[t] = overlapping_count(phase.size(), order, factors[t]);
    max_count = std::max(max_count, result.n[t]);
  }
  if (max_count == 0) return result;

  const std::size_t chunk = chunk_length(max_count, n_factors);
  const std::size_t n_chunks = (max_count + chunk - 1) / chunk;
  std::vector<double> partial(n_chunks * n_factors, 0.0);
  const auto kernel = order == 2 ? sum_sq_second_difference : sum_sq_third_difference;
  const double* x = phase.data();

  parallel_for(n_chunks, threads, [&](std::size_t c) {
    double* out = partial.data() + c * n_factors;
    const std::size_t chunk_end = std::min(max_count, (c + 1) * chunk);
    for (std::size_t k0 = c * chunk; k0 < chunk_end; k0 += kBlock) {
      const std::size_t k1 = std::min(chunk_end, k0 + kBlock);
      for (std::size_t t = 0; t < n_factors; ++t) {
        const std::size_t end = std::min(k1, result.n[t]);
        if (end > k0) out[t] += kernel(x + k0, factors[t], end - k0);
      }
    }
  });

  for (std::size_t t = 0; t < n_factors; ++t) {
    long double total = 0.0L;
    for (std::size_t c = 0; c < n_chunks; ++c) total += partial[c * n_factors + t];
    result.sum_sq[t] = static_cast<double>(total);
  }
  return result;
}

DifferenceSums strided_difference_sums(std::span<const double> phase, int order,
                                       std::span<const std::size_t> factors) {
  DifferenceSums result{std::vector<double>(factors.size(), 0.0),
                        std::vector<std::size_t>(factors.size(), 0)};
  const double* x = phase.data();
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const std::size_t m = factors[t];
    const std::size_t span = static_cast<std::size_t>(order) * m;
    if (phase.size() <= span) continue;
    long double sum = 0.0L;
    std::size_t n = 0;
    for (std::size_t k = 0; k + span < phase.size(); k += m, ++n) {
      const double d = order == 2 ? x[k + 2 * m] - 2.0 * x[k + m] + x[k]
                                  : x[k + 3 * m] - 3.0 * x[k + 2 * m] + 3.0 * x[k + m] - x[k];
      sum += static_cast<long double>(d) * d;
    }
    result.sum_sq[t] = static_cast<double>(sum);
    result.n[t] = n;
  }
  return result;
}

DifferenceSums modified_difference_sums(std::span<const double> phase,
                                        std::span<const std::size_t> factors, unsigned threads) {
  // v_j = sum_{i=j}^{j+m-1} (x[i+2m] - 2x[i+m] + x[i]) obeys
  // v_{j+1} = v_j + x[j+3m] - 3x[j+2m] + 3x[j+m] - x[j]. The recursion runs in long double,
  // where the four-term increment of doubles is exact, and restarts from a direct sum at
  // every segment, so rounding cannot build up and segments can run in parallel.
  struct Item {
    std::size_t factor;
    std::size_t begin;
    std::size_t end;
  };
  const std::size_t n_phase = phase.size();
  DifferenceSums result{std::vector<double>(factors.size(), 0.0),
                        std::vector<std::size_t>(factors.size(), 0)};
  std::vector<Item> items;
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const std::size_t m = factors[t];
    if (n_phase < 3 * m) continue;
    const std::size_t n = n_phase - 3 * m + 1;
    result.n[t] = n;
    const std::size_t segment = std::max(kMinChunk, m);  // direct restart costs O(m)
    for (std::size_t j = 0; j < n; j += segment) items.push_back({t, j, std::min(n, j + segment)});
  }
  std::vector<double> partial(items.size(), 0.0);
  const double* x = phase.data();
  parallel_for(items.size(), threads, [&](std::size_t i) {
    const Item item = items[i];
    const std::size_t m = factors[item.factor];
    long double v = 0.0L;
    for (std::size_t k = item.begin; k < item.begin + m; ++k) {
      v += static_cast<long double>(x[k + 2 * m]) - 2.0L * x[k + m] + x[k];
    }
    long double sum = 0.0L;
    for (std::size_t j = item.begin; j < item.end; ++j) {
      sum += v * v;
      if (j + 3 * m < n_phase) {
        v += (static_cast<long double>(x[j + 3 * m]) - x[j]) +
             3.0L * (static_cast<long double>(x[j + m]) - x[j + 2 * m]);
      }
    }
    partial[i] = static_cast<double>(sum);
  });
  for (std::size_t i = 0; i < items.size(); ++i) result.sum_sq[items[i].factor] += partial[i];
  return result;
}

}  // namespace imunoise::detail
