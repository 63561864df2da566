#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "imunoise/comma_list.hpp"
#include "imunoise/error.hpp"
#include "imunoise/estimator.hpp"
#include "imunoise/tau_grid.hpp"

namespace {

using imunoise::split_comma_list;
using List = std::vector<std::string>;

TEST(CommaList, ItemsAreStrippedOfBlanks) {
  EXPECT_EQ(split_comma_list("gx, gy ,\tgz"), (List{"gx", "gy", "gz"}));
  EXPECT_EQ(split_comma_list("gyro x,gyro y"), (List{"gyro x", "gyro y"}));
}

TEST(CommaList, EmptyTextIsAnEmptyListButEmptyItemsStay) {
  EXPECT_TRUE(split_comma_list("").empty());
  EXPECT_TRUE(split_comma_list("  ").empty());
  EXPECT_EQ(split_comma_list("a,,b"), (List{"a", "", "b"}));
  EXPECT_EQ(split_comma_list("a,"), (List{"a", ""}));
}

TEST(CommaList, EstimatorAndTauListsAcceptBlanks) {
  const auto list = imunoise::parse_estimator_list("oadev, mdev");
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[1], imunoise::Estimator::mdev);
  EXPECT_THROW(imunoise::parse_estimator_list(""), imunoise::InputError);
  EXPECT_THROW(imunoise::parse_estimator_list("oadev,"), imunoise::InputError);
  const auto grid = imunoise::parse_tau_grid("0.5, 2");
  ASSERT_EQ(grid.taus_s.size(), 2u);
  EXPECT_DOUBLE_EQ(grid.taus_s[1], 2.0);
}

}  // namespace
