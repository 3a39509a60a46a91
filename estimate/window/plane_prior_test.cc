#include "estimate/window/plane_prior.h"

#include <gtest/gtest.h>

namespace hapcine {
namespace {

using Ruled = std::vector<char>;

TEST(PlanePrior, TheFloorRulesOutTheBranchesWithoutIt) {
  // A dolly zoom at --fast: the two pull-back candidates have no floor parallel to the move.
  EXPECT_EQ(ContradictedByPlane({0, 0, 38}), (Ruled{1, 1, 0}));
  // --klt-window 19: a slab through a cluster on the wrong branch (29 points)
  // is under half of the floor's support.
  EXPECT_EQ(ContradictedByPlane({21, 29, 96}), (Ruled{1, 1, 0}));
  // Both on the right branch (the fit's start and the shifted solve): both keep.
  EXPECT_EQ(ContradictedByPlane({90, 100}), (Ruled{0, 0}));
}

TEST(PlanePrior, WeakPlanesAreNoEvidence) {
  EXPECT_EQ(ContradictedByPlane({0, 0, 23}), (Ruled{0, 0, 0}));
  EXPECT_EQ(ContradictedByPlane({0, 0, 0}), (Ruled{0, 0, 0}));
  EXPECT_EQ(ContradictedByPlane({}), Ruled{});
  EXPECT_EQ(ContradictedByPlane({0, 10}, 10), (Ruled{1, 0}));
}

}  // namespace
}  // namespace hapcine
