#include "imunoise/redundant/fused_csv.hpp"

#include <algorithm>
#include <functional>
#include <iterator>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "imunoise/error.hpp"
#include "imunoise/io/atomic_output.hpp"

namespace imunoise::redundant {

void write_fused_csv(const std::string& path, bool force, const FusedRecord& fused, const Unit& unit,
                     const std::string& geometry, unsigned threads) {
  // Never over an existing file without --force; written beside it and renamed on success.
  io::AtomicOutput out(path, force);
  fmt::memory_buffer buf;
  fmt::format_to(std::back_inserter(buf),
                 "# imunoise redundant: fused body rates x,y,z and {} parity residual(s) p "
                 "(p = V m) in {}; geometry {}; rate_hz {:.9g}\n",
                 fused.parity_rad_s.size(), unit.name, geometry, fused.rate_hz);
  fmt::format_to(std::back_inserter(buf), "t_s,x,y,z");
  for (std::size_t r = 0; r < fused.parity_rad_s.size(); ++r) fmt::format_to(std::back_inserter(buf), ",p{}", r + 1);
  buf.push_back('\n');
  const double f = 1.0 / unit.to_si;
  const double tau0 = 1.0 / fused.rate_hz;
  out.write(buf.data(), buf.size());
  buf.clear();
  // Formatting dominates (~20 numbers a row): blocks of rows are formatted in parallel and
  // written in order.
  constexpr std::size_t kRows = 1u << 15;
  const std::size_t workers = std::max(1u, threads ? threads : std::thread::hardware_concurrency());
  std::vector<fmt::memory_buffer> blocks(workers);
  auto format_rows = [&](std::size_t t0, std::size_t t1, fmt::memory_buffer& b) {
    b.clear();
    for (std::size_t t = t0; t < t1; ++t) {
      fmt::format_to(std::back_inserter(b), "{:.9g}", static_cast<double>(t) * tau0);
      for (const auto& a : fused.axes_rad_s) fmt::format_to(std::back_inserter(b), ",{:.9g}", a[t] * f);
      for (const auto& p : fused.parity_rad_s) fmt::format_to(std::back_inserter(b), ",{:.9g}", p[t] * f);
      b.push_back('\n');
    }
  };
  for (std::size_t start = 0; start < fused.samples; start += kRows * workers) {
    std::vector<std::thread> pool;
    for (std::size_t w = 1; w < workers; ++w) {
      const std::size_t t0 = std::min(fused.samples, start + w * kRows);
      pool.emplace_back(format_rows, t0, std::min(fused.samples, t0 + kRows), std::ref(blocks[w]));
    }
    format_rows(start, std::min(fused.samples, start + kRows), blocks[0]);
    for (auto& t : pool) t.join();
    for (const auto& b : blocks) out.write(b.data(), b.size());
    for (auto& b : blocks) b.clear();
  }
  out.commit();
}

}  // namespace imunoise::redundant
