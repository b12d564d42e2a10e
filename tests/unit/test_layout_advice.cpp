// `dustlift info`'s layout advice (solver/app/layout_advice.hpp): one rank with a thread per
// core on one machine, whatever else holds, with the reason that applies.
#include <gtest/gtest.h>

#include "solver/app/layout_advice.hpp"

using namespace dustlift;

TEST(LayoutAdvice, OneMachineRunsOneRankWithAThreadPerCore) {
  const LayoutAdvice a = recommend_layout({2, true, false});
  EXPECT_EQ(a.ranks, 1);
  EXPECT_EQ(a.threads, 2);
  EXPECT_EQ(a.command, "dustlift run SCENE -t 2");
  EXPECT_NE(a.reason.find("at least as fast as 2 MPI ranks"), std::string::npos) << a.reason;
  EXPECT_NE(a.reason.find("--map-by ppr:1:node"), std::string::npos) << a.reason;
  const LayoutAdvice eight = recommend_layout({8, true, false});
  EXPECT_EQ(eight.threads, 8);
  EXPECT_EQ(eight.command, "dustlift run SCENE -t 8");
}

TEST(LayoutAdvice, EachOtherCaseSaysWhyRanksAreNoChoice) {
  EXPECT_NE(recommend_layout({2, true, true}).reason.find("periodic channel"), std::string::npos);
  EXPECT_NE(recommend_layout({2, false, false}).reason.find("no MPI"), std::string::npos);
  const LayoutAdvice one = recommend_layout({1, true, false});
  EXPECT_EQ(one.threads, 1);
  EXPECT_NE(one.reason.find("one core"), std::string::npos);
  EXPECT_EQ(recommend_layout({0, true, false}).threads, 1);  // never fewer than one
}
