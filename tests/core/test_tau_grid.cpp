#include <gtest/gtest.h>

#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/tau_grid.hpp"

namespace imunoise {
namespace {

using Factors = std::vector<std::size_t>;

TEST(TauGrid, Octave) {
  EXPECT_EQ(averaging_factors(parse_tau_grid("octave"), 200, 100), (Factors{1, 2, 4, 8, 16, 32, 64}));
}

TEST(TauGrid, Decade) {
  EXPECT_EQ(averaging_factors(parse_tau_grid("decade"), 200, 450),
            (Factors{1, 2, 4, 10, 20, 40, 100, 200, 400}));
}

TEST(TauGrid, All) {
  EXPECT_EQ(averaging_factors(parse_tau_grid("all"), 1, 5), (Factors{1, 2, 3, 4, 5}));
}

// round(10^(i/5)) for i = 0..10: 1 2 3 4 6 10 16 25 40 63 100, with 1 and 2 not repeated.
TEST(TauGrid, PerDecadeIsLogSpacedAndUnique) {
  EXPECT_EQ(averaging_factors(parse_tau_grid("perdecade:5"), 1, 100),
            (Factors{1, 2, 3, 4, 6, 10, 16, 25, 40, 63, 100}));
  EXPECT_EQ(averaging_factors(parse_tau_grid("perdecade:10"), 1, 10),
            (Factors{1, 2, 3, 4, 5, 6, 8, 10}));
}

TEST(TauGrid, ExplicitSecondsBecomeFactors) {
  EXPECT_EQ(averaging_factors(parse_tau_grid("0.1,1,0.005"), 200, 1000), (Factors{1, 20, 200}));
}

TEST(TauGrid, ExplicitFactors) {
  EXPECT_EQ(averaging_factors(parse_factor_list("10,1,100"), 200, 1000), (Factors{1, 10, 100}));
}

TEST(TauGrid, TauBeyondDataNamesTheMaximum) {
  try {
    averaging_factors(parse_tau_grid("1,100"), 200, 1000);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("maximum"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("5 s"), std::string::npos) << e.what();
  }
}

TEST(TauGrid, BadSpecificationsAreErrors) {
  EXPECT_THROW(parse_tau_grid(""), InputError);
  EXPECT_THROW(parse_tau_grid("weekly"), InputError);
  EXPECT_THROW(parse_tau_grid("perdecade:0"), InputError);
  EXPECT_THROW(parse_tau_grid("-1"), InputError);
  EXPECT_THROW(parse_tau_grid("1,nan"), InputError);
  EXPECT_THROW(parse_factor_list("1.5"), InputError);
  EXPECT_THROW(averaging_factors(parse_tau_grid("0.0073"), 200, 1000), InputError);
}

TEST(Estimators, NamesRoundTripAndUnknownIsAnError) {
  for (const Estimator e : all_estimators()) EXPECT_EQ(parse_estimator(estimator_name(e)), e);
  EXPECT_THROW(parse_estimator("allan"), InputError);
  EXPECT_EQ(parse_estimator_list("all").size(), all_estimators().size());
  EXPECT_EQ(parse_estimator_list("oadev,mdev"), (std::vector{Estimator::oadev, Estimator::mdev}));
  EXPECT_THROW(parse_estimator_list("oadev,oadev"), InputError);
  EXPECT_THROW(parse_estimator_list("oadev,"), InputError);
}

}  // namespace
}  // namespace imunoise
