// Overlapping Allan deviation of the NBS14 10-point set at tau = 1 s and 2 s, printed with
// its unit; exits non-zero unless the published values (NIST SP 1065) come out.
#include <cmath>
#include <cstdio>
#include <vector>

#include <imunoise/allan.hpp>
#include <imunoise/phase.hpp>

int main() {
  const std::vector<double> frequency{892, 809, 823, 798, 671, 644, 883, 903, 677};
  const auto phase = imunoise::phase_from_rate(frequency, 1.0, imunoise::compensated_mean(frequency));
  const std::vector<std::size_t> factors{1, 2};
  const auto points = imunoise::oadev(phase, 1.0, factors);
  const double published[] = {91.22945, 85.95287};
  bool ok = points.size() == 2;
  for (std::size_t i = 0; ok && i < points.size(); ++i) {
    std::printf("tau = %g s  oadev = %.7g (fractional frequency)\n", points[i].tau_s, points[i].dev);
    ok = std::abs(points[i].dev / published[i] - 1.0) < 6e-7;
  }
  return ok ? 0 : 1;
}
