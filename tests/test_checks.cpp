// DLAB_ASSERT: aborts with the condition and message where checks are on (Debug, sanitizers,
// DLAB_CHECKS), and costs nothing elsewhere: the condition is not even evaluated.
#include "core/engine/checks.h"

#include <gtest/gtest.h>

TEST(Checks, ConditionIsEvaluatedOnlyWhereChecksAreOn) {
    int evaluated = 0;
    DLAB_ASSERT(++evaluated > 0, "never fails");
    EXPECT_EQ(evaluated, DLAB_CHECKS_ON ? 1 : 0);
}

TEST(Checks, FailedCheckAbortsNamingConditionAndMessage) {
    if (!DLAB_CHECKS_ON) GTEST_SKIP() << "checks are compiled out of this build";
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(DLAB_ASSERT(1 + 1 == 3, "arithmetic broke"),
                 "DLAB_ASSERT\\(1 \\+ 1 == 3\\) failed: arithmetic broke");
}
