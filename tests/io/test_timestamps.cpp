// Timestamps: derived rate, jitter, gaps and disorder with exact expected counts; precise
// nanosecond handling; the messages of require_ordered / require_no_gaps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "imunoise/io/text_reader.hpp"
#include "imunoise/io/timestamps.hpp"
#include "io_test_support.hpp"

namespace imunoise::io {
namespace {

using test::expect_input_error;

std::vector<double> regular_times(std::size_t n, double rate_hz, double start_s = 0.0) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = start_s + static_cast<double>(i) / rate_hz;
  return t;
}

TEST(Timing, RegularRecord) {
  const auto t = regular_times(1000, 200.0, 1234.5);
  const TimingReport report = check_timing(t, "reg.csv");
  EXPECT_EQ(report.n_samples, 1000u);
  EXPECT_NEAR(report.rate_hz, 200.0, 1e-6);
  EXPECT_NEAR(report.median_dt_s, 0.005, 1e-12);
  EXPECT_NEAR(report.duration_s, 999 * 0.005, 1e-9);
  EXPECT_LT(report.jitter_rel_max, 1e-6);  // only rounding of the times
  EXPECT_TRUE(report.gaps.empty());
  EXPECT_TRUE(report.disorder.empty());
  EXPECT_EQ(report.missing_samples, 0u);
}

TEST(Timing, GapsWithExactCounts) {
  // 100 Hz, samples 100..102 and 500 removed: two gaps, 3 and 1 missing.
  std::vector<double> t;
  for (int i = 0; i < 1000; ++i) {
    if ((i >= 100 && i <= 102) || i == 500) continue;
    t.push_back(i * 0.01);
  }
  const TimingReport report = analyze_timing(t, "gaps.csv");
  EXPECT_NEAR(report.rate_hz, 100.0, 1e-9);
  ASSERT_EQ(report.gaps.size(), 2u);
  EXPECT_EQ(report.gaps[0].index, 100u);  // sample 103 of the original is now index 100
  EXPECT_EQ(report.gaps[0].missing_samples, 3u);
  EXPECT_NEAR(report.gaps[0].duration_s, 0.04, 1e-12);
  EXPECT_EQ(report.gaps[1].index, 497u);  // original sample 501, after 4 removed
  EXPECT_EQ(report.gaps[1].missing_samples, 1u);
  EXPECT_EQ(report.missing_samples, 4u);
  EXPECT_FALSE(report.gaps[0].line.has_value());
  EXPECT_TRUE(report.disorder.empty());
  // Gaps do not count as jitter.
  EXPECT_LT(report.jitter_rel_max, 1e-9);

  const std::string message = expect_input_error(
      [&] { require_no_gaps(report, "gaps.csv"); },
      {"gaps.csv: sample 100", "time gap of 0.04 s", "3 missing at 100 Hz", "2 gap(s)",
       "4 missing sample(s)", "split the record at the gap", "--allow-gaps",
       "never interpolates"});
  EXPECT_NO_THROW(check_timing(t, "gaps.csv", nullptr, /*allow_gaps=*/true));
  EXPECT_THROW(check_timing(t, "gaps.csv"), InputError);
}

TEST(Timing, JitterStatistics) {
  // Intervals alternate 9 ms / 11 ms: median 10 ms, every deviation 10 %.
  std::vector<double> t{0.0};
  const std::size_t intervals = 400;
  for (std::size_t i = 0; i < intervals; ++i) t.push_back(t.back() + (i % 2 == 0 ? 0.009 : 0.011));
  const TimingReport report = check_timing(t, "jit.csv");
  EXPECT_NEAR(report.median_dt_s, 0.01, 1e-12);
  EXPECT_NEAR(report.rate_hz, 100.0, 1e-8);
  EXPECT_NEAR(report.jitter_rel_max, 0.1, 1e-9);
  // Sample standard deviation of +-1 ms about a 10 ms mean: 1 ms * sqrt(n / (n - 1)).
  const double n = static_cast<double>(intervals);
  EXPECT_NEAR(report.jitter_rel_std, 0.1 * std::sqrt(n / (n - 1.0)), 1e-9);
  EXPECT_TRUE(report.gaps.empty());
}

TEST(Timing, OutOfOrderAndDuplicates) {
  std::vector<double> t = regular_times(100, 10.0);
  std::swap(t[40], t[41]);  // one step back at index 41
  t[70] = t[69];            // a duplicate at 70 (and a 2-interval step after it -> gap at 71)
  const TimingReport report = analyze_timing(t, "order.csv");
  ASSERT_EQ(report.disorder.size(), 2u);
  EXPECT_EQ(report.disorder[0].index, 41u);
  EXPECT_NEAR(report.disorder[0].time_s, 4.0, 1e-12);
  EXPECT_NEAR(report.disorder[0].previous_time_s, 4.1, 1e-12);
  EXPECT_EQ(report.disorder[1].index, 70u);
  // The swap makes 2-interval steps into and out of the pair (indices 40 and 42), the
  // duplicate one after it (index 71).
  ASSERT_EQ(report.gaps.size(), 3u);
  EXPECT_EQ(report.gaps[0].index, 40u);
  EXPECT_EQ(report.gaps[1].index, 42u);
  EXPECT_EQ(report.gaps[2].index, 71u);
  expect_input_error([&] { require_ordered(report, "order.csv"); },
                     {"order.csv: sample 41", "its time 4 s is before the previous sample's 4.1 s",
                      "2 sample(s) are out of order or duplicated", "sort the file",
                      "remove duplicate rows"});
  std::vector<double> dup = regular_times(10, 1.0);
  dup[5] = dup[4];
  expect_input_error([&] { check_timing(dup, "dup.csv", nullptr, true); },
                     {"dup.csv: sample 5", "duplicates the previous sample's 4 s"});
}

TEST(Timing, LinesFromTheTextReader) {
  const std::string text =
      "# t gx\n"
      "t,gx\n"
      "0.00,1\n"
      "0.01,1\n"
      "# operator paused logging\n"
      "0.05,1\n"
      "0.06,1\n"
      "0.07,1\n";
  TextReadOptions options;
  options.time_column = std::string("t");
  const TextColumns columns = read_text_buffer(text, "log.csv", options);
  const TimingReport report = analyze_timing(columns.time_s, columns.source, &columns.lines);
  ASSERT_EQ(report.gaps.size(), 1u);
  EXPECT_EQ(report.gaps[0].index, 2u);
  EXPECT_EQ(report.gaps[0].line, std::optional<std::size_t>(6));
  EXPECT_EQ(report.gaps[0].missing_samples, 3u);
  EXPECT_NEAR(report.rate_hz, 100.0, 1e-9);
  expect_input_error([&] { require_no_gaps(report, columns.source); },
                     {"log.csv:6: sample 2", "time gap of 0.04 s", "1 gap(s)"});
}

TEST(Timing, InvalidTimes) {
  expect_input_error([] { analyze_timing(std::vector<double>{1.0}, "one.csv"); },
                     {"one.csv:", "1 timestamp", "at least 2"});
  expect_input_error([] { analyze_timing(std::vector<double>{}, "none.csv"); }, {"0 timestamp"});
  expect_input_error(
      [] {
        analyze_timing(std::vector<double>{0.0, std::numeric_limits<double>::quiet_NaN(), 2.0}, "n.csv");
      },
      {"n.csv: sample 1", "nan"});
  // Mostly duplicates: the median interval is 0, so there is no rate.
  expect_input_error([] { analyze_timing(std::vector<double>{1, 1, 1, 1, 2}, "z.csv"); },
                     {"z.csv:", "median interval", "no positive sample rate"});
  expect_input_error([] { analyze_timing(std::vector<double>{5, 4, 3, 2}, "neg.csv"); },
                     {"neg.csv:", "-1 s", "no positive sample rate"});
  const double huge = std::numeric_limits<double>::max();
  expect_input_error([&] { analyze_timing(std::vector<double>{-huge, huge, -huge, huge}, "inf.csv"); },
                     {"inf.csv:", "median interval", "no positive sample rate"});
}

TEST(SplitTime, ParsesPlainDecimalsExactly) {
  auto t = parse_split_time("1600000000123456789");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->whole, 1'600'000'000'123'456'789);
  EXPECT_EQ(t->fraction, 0.0);
  EXPECT_TRUE(t->integer);
  t = parse_split_time("-12.25");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->whole, -12);
  EXPECT_EQ(t->fraction, -0.25);
  EXPECT_FALSE(t->integer);
  t = parse_split_time("+7.");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->whole, 7);
  EXPECT_EQ(t->fraction, 0.0);
  t = parse_split_time("1.5e3");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->whole, 0);
  EXPECT_EQ(t->fraction, 1500.0);
  t = parse_split_time("123456789012345678901234");  // beyond int64: kept as a double
  ASSERT_TRUE(t);
  EXPECT_EQ(t->fraction, 123456789012345678901234.0);
  EXPECT_FALSE(parse_split_time("12:30"));
  EXPECT_FALSE(parse_split_time(""));
  EXPECT_FALSE(parse_split_time("-"));
  EXPECT_FALSE(is_finite(*parse_split_time("inf")));
}

TEST(SplitTime, NanosecondDetection) {
  const std::vector<SplitTime> ns{{1'600'000'000'000'000'000, 0.0, true}, {1'600'000'000'005'000'000, 0.0, true}};
  EXPECT_TRUE(looks_like_nanoseconds(ns));
  const std::vector<SplitTime> seconds{{1'700'000'000, 0.5, false}, {1'700'000'001, 0.0, true}};
  EXPECT_FALSE(looks_like_nanoseconds(seconds));
  const std::vector<SplitTime> small_ints{{1000, 0.0, true}, {1001, 0.0, true}};
  EXPECT_FALSE(looks_like_nanoseconds(small_ints));
  EXPECT_FALSE(looks_like_nanoseconds({}));
}

TEST(SplitTime, RelativeSecondsFromNanoseconds) {
  const std::vector<std::int64_t> stamps{1'600'000'000'123'456'789, 1'600'000'000'128'456'790,
                                         1'600'000'000'133'456'789};
  const auto t = relative_seconds_from_ns(stamps);
  EXPECT_EQ(t, (std::vector<double>{0.0, 0.005000001, 0.01}));
  // As plain doubles the same stamps could not resolve that nanosecond.
  const double naive = static_cast<double>(stamps[1]) - static_cast<double>(stamps[0]);
  EXPECT_NE(naive * 1e-9, 0.005000001);
  EXPECT_TRUE(relative_seconds_from_ns({}).empty());
  // Extreme spans fall back to double arithmetic instead of overflowing.
  const std::vector<std::int64_t> extreme{std::numeric_limits<std::int64_t>::min(),
                                          std::numeric_limits<std::int64_t>::max()};
  EXPECT_NEAR(relative_seconds_from_ns(extreme)[1], 18446744073.709552, 1e-5);
}

}  // namespace
}  // namespace imunoise::io
