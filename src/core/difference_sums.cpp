#include "difference_sums.hpp"

#include <algorithm>

#include "correlation_sums.hpp"
#include "kernels.hpp"
#include "parallel.hpp"
#include "prefaulted.hpp"

namespace imunoise::detail {
namespace {

// Start indices are processed in blocks small enough that the few windows one block reads
// for all factors stay in L2 (for octave factors the window at offset 2m is the window at
// offset m of the next factor). Blocks are grouped into super-chunks, the unit of work for a
// thread; each super-chunk writes its own partial sums, which are reduced in a fixed order,
// so results are bitwise identical for any thread count.
constexpr std::size_t kBlock = 4096;
// Many near factors (every factor, or a dense grid) are mostly consecutive: the windows of one
// factor overlap the next one's, so with blocks of 1024 starts (3 windows of 8 KB) a block's
// windows stay in L1 across factors. Measured on `--taus all` (1e5 samples): 22 % less time;
// for a few far-apart factors (octave) the larger block is 8 % faster, so it stays theirs.
constexpr std::size_t kDenseBlock = 1024;
constexpr std::size_t kDenseFactors = 256;
constexpr std::size_t kMinChunk = 65536;
constexpr std::size_t kMaxPartials = std::size_t{1} << 23;  // 64 MB of partial sums at most
// Modified Allan: factors up to this run together over chunks of starts (their segments, at
// most 16 m long, fit in a chunk); larger ones run alone over segments of at least 4 m.
constexpr std::size_t kSmallWindowFactor = kMinChunk / 16;
// Powers of two up to this run by doubling (sum_sq_window_doubling_step): a chunk's octaves
// from one array of D_m, four operations per start and octave instead of the window
// recursion's prefix sum in registers. Each chunk also builds the lower octaves up to
// ~3 kDoublingFactor past its end for the higher ones.
constexpr std::size_t kDoublingFactor = 1024;

bool is_power_of_two(std::size_t m) { return m != 0 && (m & (m - 1)) == 0; }

// The octave factors 1, 2, 4, ... 2^top of one chunk of starts [begin, end) by doubling, the
// sums of the requested ones into sums[] (indexed like `octave`). n_of(t) is factor t's
// number of windows; d is scratch.
template <class WindowCount>
void doubling_chunk(const double* x, std::span<const std::size_t> octave,
                    std::span<const std::size_t> factors, WindowCount n_of, std::size_t begin,
                    std::size_t end, std::vector<double>& d, double* sums) {
  const std::size_t top = factors[octave.back()];
  std::size_t levels = 0;
  while ((std::size_t{1} << levels) <= top) ++levels;
  // count[p]: windows of octave p in this chunk (0 when not requested); need[p]: the D_2^p
  // entries that octave p and every higher one read.
  std::vector<std::size_t> count(levels, 0), need(levels + 1, 0);
  std::vector<std::ptrdiff_t> slot(levels, -1);
  for (std::size_t f = 0; f < octave.size(); ++f) {
    const std::size_t m = factors[octave[f]];
    std::size_t p = 0;
    while ((std::size_t{1} << p) < m) ++p;
    const std::size_t n = n_of(octave[f]);
    count[p] = n > begin ? std::min(end, n) - begin : 0;
    slot[p] = static_cast<std::ptrdiff_t>(f);
  }
  for (std::size_t p = levels; p-- > 0;) {
    const std::size_t m = std::size_t{1} << p;
    const std::size_t own = count[p] > 0 ? count[p] + m : 0;
    const std::size_t higher = need[p + 1] > 0 ? need[p + 1] + 2 * m : 0;
    need[p] = std::max(own, higher);
  }
  if (need[0] == 0) {
    for (std::size_t f = 0; f < octave.size(); ++f) sums[f] = 0.0;
    return;
  }
  d.resize(std::max<std::size_t>(need[1], 1));
  // The chunk's mean phase increment (a rate offset): removed from D, see the kernel.
  const double slope = (x[begin + need[0]] - x[begin]) / static_cast<double>(need[0]);
  for (std::size_t p = 0; p < levels; ++p) {
    const double sum = p == 0 ? sum_sq_window_doubling_first(x + begin, count[0], need[1], slope, d.data())
                              : sum_sq_window_doubling_step(d.data(), std::size_t{1} << p, count[p], need[p + 1]);
    if (slot[p] >= 0) sums[slot[p]] = sum;
  }
}

std::size_t chunk_length(std::size_t n_starts, std::size_t n_factors, std::size_t min_chunk = kMinChunk) {
  std::size_t chunk = min_chunk;
  while ((n_starts / chunk + 1) * n_factors > kMaxPartials) chunk *= 2;
  return chunk;
}

// Far factors view x as a matrix with `columns` columns (a power of two) and at most
// kMaxTileRows rows. A factor m that is a multiple of `columns` is a lag of m/columns rows,
// so its terms for a tile of kTileWidth columns only involve that tile: gathered once into a
// contiguous buffer (1 MB, in L2) it serves every far factor. Gathering beats reading the
// tile in place: rows a power of two apart would all fall into the same few cache sets.
constexpr std::size_t kTileWidth = 64;
constexpr std::size_t kMaxTileRows = 2048;
std::size_t matrix_columns(std::size_t n_phase) {
  std::size_t columns = 2 * kTileWidth;
  while (n_phase / columns > kMaxTileRows) columns *= 2;
  return columns;
}

// Copies rows [0, rows) of columns [c0, c0 + kTileWidth) of the matrix view into `tile`
// (row-major, kTileWidth wide); cells past the end of x are zero and never used.
void gather_tile(std::span<const double> x, std::size_t columns, std::size_t c0,
                 std::size_t rows, std::vector<double>& tile) {
  // Only the ragged end is zeroed: clearing the whole megabyte per tile would cost more
  // memory traffic than the gather itself.
  resize_prefaulted(tile, rows * kTileWidth);
  for (std::size_t r = 0; r < rows; ++r) {
    const std::size_t begin = r * columns + c0;
    double* row = tile.data() + r * kTileWidth;
    const std::size_t len = begin < x.size() ? std::min(kTileWidth, x.size() - begin) : 0;
    if (len > 0) std::copy_n(x.data() + begin, len, row);
    std::fill(row + len, row + kTileWidth, 0.0);
  }
}

// A factor's correlation sum replaces the direct one when its rounding bound is this small
// (relative; the bound has a factor 13 to spare over the largest error measured, and the
// direct sums themselves round at ~1e-15): within 1e-12 of the direct sum with room.
constexpr double kExactEnough = 5e-13;
// Direct terms above which every factor's sums are worth the correlations' transforms.
constexpr std::size_t kCorrelationTerms = std::size_t{1} << 29;

std::size_t direct_terms(std::span<const std::size_t> counts, std::span<const std::size_t> selected) {
  std::size_t terms = 0;
  for (const std::size_t t : selected) terms += counts[t];
  return terms;
}

std::size_t overlapping_count(std::size_t n_phase, int order, std::size_t m) {
  const std::size_t span = static_cast<std::size_t>(order) * m;
  return n_phase > span ? n_phase - span : 0;
}

}  // namespace

DifferenceSums overlapping_difference_sums(std::span<const double> phase, int order,
                                           std::span<const std::size_t> factors, unsigned threads) {
  const std::size_t n_phase = phase.size();
  const std::size_t n_factors = factors.size();
  DifferenceSums result{std::vector<double>(n_factors, 0.0), std::vector<std::size_t>(n_factors)};
  for (std::size_t t = 0; t < n_factors; ++t) {
    result.n[t] = overlapping_count(n_phase, order, factors[t]);
  }

  // Near factors run over contiguous blocks of start indices; far factors (multiples of the
  // column count of the matrix view, see kernels.hpp) run down column tiles. Either way each
  // cache line of x comes from memory about once per pass instead of once per factor.
  // With a dense grid (every factor) the multiples of the column count stay near: taken out,
  // they would break the runs of eight consecutive factors around them (1e5 samples, every
  // factor: 11 % of the time went to the one-factor kernel for the factors left over).
  const std::size_t columns = matrix_columns(n_phase);
  const bool dense = n_factors > kDenseFactors;
  std::vector<std::size_t> near, far;
  for (std::size_t t = 0; t < n_factors; ++t) {
    if (result.n[t] == 0) continue;
    (!dense && factors[t] % columns == 0 ? far : near).push_back(t);
  }
  // Every factor of a long record: the sums come from correlations (correlation_sums.hpp),
  // O(N log^2 N) for all of them instead of O(N) each, except where the rounding bound rejects
  // them (small m, few starts): those few stay direct. 1e6 samples: 2.5e11 terms.
  if (dense && direct_terms(result.n, near) >= kCorrelationTerms) {
    std::vector<std::size_t> near_factors(near.size());
    for (std::size_t i = 0; i < near.size(); ++i) near_factors[i] = factors[near[i]];
    const CorrelationSums sums = correlation_difference_sums(phase, order, near_factors, threads);
    std::vector<std::size_t> rejected;
    for (std::size_t i = 0; i < near.size(); ++i) {
      if (sums.relative_bound[i] <= kExactEnough) {
        result.sum_sq[near[i]] = sums.sum_sq[i];
      } else {
        rejected.push_back(near[i]);
      }
    }
    near = std::move(rejected);
  }
  // In increasing m, so the counts of starts fall along `near` and a block can stop at the
  // first factor that has ended (with every factor most have, in most blocks).
  std::stable_sort(near.begin(), near.end(), [&](std::size_t a, std::size_t b) { return factors[a] < factors[b]; });
  std::size_t near_count = 0;
  for (const std::size_t t : near) near_count = std::max(near_count, result.n[t]);
  // Every factor's work falls off along the record (factor m has n - 2m starts): with chunks
  // of 65,536 starts a 1e5 record was two chunks of unequal work and the second core idled.
  const std::size_t chunk = chunk_length(near_count, near.size(), dense ? 8 * kDenseBlock : kMinChunk);
  const std::size_t n_chunks = near.empty() ? 0 : (near_count + chunk - 1) / chunk;
  const std::size_t n_tiles = far.empty() ? 0 : columns / kTileWidth;

  std::vector<double> near_partial;  // 64 MB with every factor of 1e6 samples: mapped in bulk
  resize_prefaulted(near_partial, n_chunks * near.size());
  std::vector<double> far_partial(n_tiles * far.size(), 0.0);
  const auto kernel = order == 2 ? sum_sq_second_difference : sum_sq_third_difference;
  const double* x = phase.data();

  const std::size_t block = near.size() > kDenseFactors ? kDenseBlock : kBlock;
  // Runs of eight consecutive near factors (every factor, or a dense grid) share their windows:
  // one kernel call reads each sample once for all eight. run_at[i]: near[i] starts a run.
  std::vector<char> run_at(near.size(), 0);
  if (difference_runs_available()) {
    for (std::size_t i = 0; i + 8 <= near.size();) {
      bool consecutive = true;
      for (std::size_t j = 1; j < 8 && consecutive; ++j) consecutive = factors[near[i + j]] == factors[near[i]] + j;
      if (consecutive) {
        run_at[i] = 1;
        i += 8;
      } else {
        ++i;
      }
    }
  }
  const auto run_kernel = order == 2 ? sum_sq_second_difference_run8 : sum_sq_third_difference_run8;
  auto run_chunk = [&](std::size_t c) {
    double* out = near_partial.data() + c * near.size();
    const std::size_t chunk_end = std::min(near_count, (c + 1) * chunk);
    for (std::size_t k0 = c * chunk; k0 < chunk_end; k0 += block) {
      const std::size_t k1 = std::min(chunk_end, k0 + block);
      for (std::size_t i = 0; i < near.size() && result.n[near[i]] > k0;) {
        // The run's common starts are those of its largest factor (the fewest terms); the
        // smaller factors' extra starts at the record's end go through the one-factor kernel.
        const std::size_t common_end = run_at[i] ? std::min(k1, result.n[near[i + 7]]) : 0;
        if (common_end > k0) {
          double sums[8];
          run_kernel(x + k0, factors[near[i]], common_end - k0, result.n[near[i + 7]] - k0, sums);
          for (std::size_t j = 0; j < 8; ++j) {
            out[i + j] += sums[j];
            const std::size_t end = std::min(k1, result.n[near[i + j]]);
            if (end > common_end) out[i + j] += kernel(x + common_end, factors[near[i + j]], end - common_end);
          }
          i += 8;
          continue;
        }
        const std::size_t end = std::min(k1, result.n[near[i]]);
        if (end > k0) out[i] += kernel(x + k0, factors[near[i]], end - k0);
        ++i;
      }
    }
  };
  const std::size_t rows = (n_phase + columns - 1) / columns;
  auto run_tile = [&](std::size_t tile_index) {
    thread_local std::vector<double> tile;
    const std::size_t c0 = tile_index * kTileWidth;
    gather_tile(phase, columns, c0, rows, tile);
    double* out = far_partial.data() + tile_index * far.size();
    for (std::size_t i = 0; i < far.size(); ++i) {
      const std::size_t m = factors[far[i]];
      const std::size_t span = static_cast<std::size_t>(order) * m;
      const std::size_t lag = m / columns * kTileWidth;  // m samples = m/columns tile rows
      // Start k = r*columns + c is valid while k + span <= n_phase - 1: rows valid for every
      // column of the tile run contiguously; the (at most one) ragged row is done per column.
      auto valid_rows = [&](std::size_t c) -> std::size_t {
        return c + span <= n_phase - 1 ? (n_phase - 1 - span - c) / columns + 1 : 0;
      };
      const std::size_t full = valid_rows(c0 + kTileWidth - 1);
      double sum = full > 0 ? kernel(tile.data(), lag, full * kTileWidth) : 0.0;
      for (std::size_t c = 0; c < kTileWidth; ++c) {
        if (valid_rows(c0 + c) > full) sum += kernel(tile.data() + full * kTileWidth + c, lag, 1);
      }
      out[i] = sum;
    }
  };
  parallel_for(n_chunks + n_tiles, threads, [&](std::size_t item) {
    if (item < n_chunks) {
      run_chunk(item);
    } else {
      run_tile(item - n_chunks);
    }
  });

  for (std::size_t i = 0; i < near.size(); ++i) {
    long double total = 0.0L;
    for (std::size_t c = 0; c < n_chunks; ++c) total += near_partial[c * near.size() + i];
    result.sum_sq[near[i]] = static_cast<double>(total);
  }
  for (std::size_t i = 0; i < far.size(); ++i) {
    long double total = 0.0L;
    for (std::size_t tile = 0; tile < n_tiles; ++tile) total += far_partial[tile * far.size() + i];
    result.sum_sq[far[i]] = static_cast<double>(total);
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
  // v_j = sum_{i=j}^{j+m-1} (x[i+2m] - 2x[i+m] + x[i]) runs as v_{j+1} = v_j + e_{j+m} - e_j in
  // the vector kernel, restarted from a direct sum at every segment so that rounding cannot
  // build up (the longer segments of large factors have windows large enough to absorb it) and
  // segments can run in parallel. Small factors run together over chunks of starts, as oadev's
  // near factors do: a chunk of x (half a megabyte) stays in cache for all of them, so the record
  // comes from memory about once for all small factors instead of once per factor.
  const std::size_t n_phase = phase.size();
  DifferenceSums result{std::vector<double>(factors.size(), 0.0),
                        std::vector<std::size_t>(factors.size(), 0)};
  // Far factors (multiples of the matrix view's column count, as for oadev) run down gathered
  // column tiles: the window at the start of each tile row comes from long-double prefix sums
  // of the phase at multiples of 64 (O(1) per row instead of a direct sum), the other 63 from
  // the recursion down the tile, so one tile serves every far factor from cache.
  const std::size_t columns = matrix_columns(n_phase);
  std::vector<std::size_t> small, octave, large, far;
  std::size_t small_count = 0;
  for (std::size_t t = 0; t < factors.size(); ++t) {
    const std::size_t m = factors[t];
    if (m == 0 || n_phase < 3 * m) continue;
    result.n[t] = n_phase - 3 * m + 1;
    if (m % columns == 0) {
      far.push_back(t);
    } else if (m <= kDoublingFactor && is_power_of_two(m) &&
               std::none_of(octave.begin(), octave.end(), [&](std::size_t o) { return factors[o] == m; })) {
      octave.push_back(t);
      small_count = std::max(small_count, result.n[t]);
    } else if (m <= kSmallWindowFactor) {
      small.push_back(t);
      small_count = std::max(small_count, result.n[t]);
    } else {
      large.push_back(t);
    }
  }
  // Restart segment of a factor: kBlock windows while the direct sum is cheap, longer (up to a
  // chunk) for larger m, so the restart costs at most 1/16 of the segment.
  auto segment_of = [](std::size_t m) { return std::max(kBlock, 16 * m); };
  struct Item {
    std::size_t factor;  // index into factors; SIZE_MAX for a chunk of all small factors
    std::size_t begin;
    std::size_t end;
  };
  constexpr std::size_t kAllSmall = static_cast<std::size_t>(-1);
  std::vector<Item> items;
  // Large factors first: their segments are the longest items, so the threads finish together.
  for (auto it = large.rbegin(); it != large.rend(); ++it) {
    const std::size_t n = result.n[*it];
    const std::size_t segment = std::max(kMinChunk, 4 * factors[*it]);
    for (std::size_t j = 0; j < n; j += segment) items.push_back({*it, j, std::min(n, j + segment)});
  }
  std::sort(octave.begin(), octave.end(), [&](std::size_t a, std::size_t b) { return factors[a] < factors[b]; });
  if (!small.empty() || !octave.empty()) {
    for (std::size_t j = 0; j < small_count; j += kMinChunk) {
      items.push_back({kAllSmall, j, std::min(small_count, j + kMinChunk)});
    }
  }
  constexpr std::size_t kFarTile = static_cast<std::size_t>(-2);
  const std::size_t n_tiles = far.empty() ? 0 : columns / kTileWidth;
  for (std::size_t tile = 0; tile < n_tiles; ++tile) items.push_back({kFarTile, tile, tile});
  // S(64 g) = sum_{i < 64 g} x_i, g = 0 .. n_phase / 64, in long double (fixed blocks: any
  // thread count gives the same bits).
  std::vector<long double> prefix64;
  const double* x = phase.data();
  if (!far.empty()) {
    const std::size_t segments = n_phase / kTileWidth;
    // Megabytes per call (1e7 samples: 2.5 MB each): mapped in bulk, not faulted page by page
    // (a third of mdev's time on a VM went to those faults).
    std::vector<long double> segment_sum;
    resize_prefaulted(segment_sum, segments);
    constexpr std::size_t kSegmentsPerItem = 4096;
    parallel_for((segments + kSegmentsPerItem - 1) / kSegmentsPerItem, threads, [&](std::size_t item) {
      const std::size_t end = std::min(segments, (item + 1) * kSegmentsPerItem);
      for (std::size_t g = item * kSegmentsPerItem; g < end; ++g) {
        const double* p = x + g * kTileWidth;
        // Long double: each segment's rounding would otherwise build up along the prefix.
        long double s0 = 0.0L, s1 = 0.0L, s2 = 0.0L, s3 = 0.0L;
        for (std::size_t i = 0; i < kTileWidth; i += 4) {
          s0 += p[i];
          s1 += p[i + 1];
          s2 += p[i + 2];
          s3 += p[i + 3];
        }
        segment_sum[g] = (s0 + s1) + (s2 + s3);
      }
    });
    resize_prefaulted(prefix64, segments + 1);
    prefix64[0] = 0.0L;
    for (std::size_t g = 0; g < segments; ++g) prefix64[g + 1] = prefix64[g] + segment_sum[g];
  }
  const std::size_t tile_rows = (n_phase + columns - 1) / columns + 1;  // + 1: reads past the end
  auto run_far_tile = [&](std::size_t tile_index, double* out) {
    thread_local std::vector<double> tile;
    thread_local std::vector<double> starts;
    const std::size_t c0 = tile_index * kTileWidth;
    gather_tile(phase, columns, c0, tile_rows, tile);
    for (std::size_t f = 0; f < far.size(); ++f) {
      const std::size_t m = factors[far[f]];
      const std::size_t last = n_phase - 3 * m;  // last window start
      if (c0 > last) {
        out[f] = 0.0;
        continue;
      }
      const std::size_t any_rows = (last - c0) / columns + 1;  // rows with a window
      const std::size_t full_rows =
          last >= c0 + kTileWidth - 1 ? (last - c0 - (kTileWidth - 1)) / columns + 1 : 0;
      const std::size_t a = m / kTileWidth;
      starts.resize(any_rows);
      for (std::size_t r = 0; r < any_rows; ++r) {
        const std::size_t g = (r * columns + c0) / kTileWidth;
        starts[r] = static_cast<double>((prefix64[g + 3 * a] - prefix64[g]) -
                                        3.0L * (prefix64[g + 2 * a] - prefix64[g + a]));
      }
      const std::size_t lag = m / columns * kTileWidth;
      double sum = sum_sq_window_tile_rows(tile.data(), lag, starts.data(), full_rows);
      for (std::size_t r = full_rows; r < any_rows; ++r) {  // the ragged last row
        const double* t0 = tile.data() + r * kTileWidth;
        const std::size_t valid = std::min(kTileWidth, last - (r * columns + c0) + 1);
        double v = starts[r];
        for (std::size_t c = 0; c < valid; ++c) {
          sum += v * v;
          const double e_hi = (t0[c + 3 * lag] - 2.0 * t0[c + 2 * lag]) + t0[c + lag];
          const double e_lo = (t0[c + 2 * lag] - 2.0 * t0[c + lag]) + t0[c];
          v += e_hi - e_lo;
        }
      }
      out[f] = sum;
    }
  };
  // One slot per (item, factor it covers): large items cover one factor, chunks all small ones,
  // tiles all far ones.
  std::vector<std::size_t> slot(items.size() + 1, 0);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const std::size_t covers = items[i].factor == kAllSmall  ? small.size() + octave.size()
                               : items[i].factor == kFarTile ? far.size()
                                                             : 1;
    slot[i + 1] = slot[i] + covers;
  }
  std::vector<double> partial(slot.back(), 0.0);
  parallel_for(items.size(), threads, [&](std::size_t i) {
    const Item item = items[i];
    if (item.factor == kFarTile) {
      run_far_tile(item.begin, partial.data() + slot[i]);
      return;
    }
    if (item.factor != kAllSmall) {
      partial[slot[i]] = sum_sq_window_second_difference(x + item.begin, factors[item.factor],
                                                         item.end - item.begin);
      return;
    }
    for (std::size_t f = 0; f < small.size(); ++f) {
      const std::size_t m = factors[small[f]];
      const std::size_t end = std::min(item.end, result.n[small[f]]);
      const std::size_t segment = segment_of(m);
      double sum = 0.0;
      for (std::size_t j = item.begin; j < end; j += segment) {
        sum += sum_sq_window_second_difference(x + j, m, std::min(end, j + segment) - j);
      }
      partial[slot[i] + f] = sum;
    }
    if (!octave.empty()) {
      thread_local std::vector<double> d;
      doubling_chunk(x, octave, factors, [&](std::size_t t) { return result.n[t]; }, item.begin,
                     item.end, d, partial.data() + slot[i] + small.size());
    }
  });
  std::vector<long double> totals(factors.size(), 0.0L);
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].factor == kFarTile) {
      for (std::size_t f = 0; f < far.size(); ++f) totals[far[f]] += partial[slot[i] + f];
    } else if (items[i].factor != kAllSmall) {
      totals[items[i].factor] += partial[slot[i]];
    } else {
      for (std::size_t f = 0; f < small.size(); ++f) totals[small[f]] += partial[slot[i] + f];
      for (std::size_t f = 0; f < octave.size(); ++f) totals[octave[f]] += partial[slot[i] + small.size() + f];
    }
  }
  for (std::size_t t = 0; t < factors.size(); ++t) result.sum_sq[t] = static_cast<double>(totals[t]);
  return result;
}

}  // namespace imunoise::detail
