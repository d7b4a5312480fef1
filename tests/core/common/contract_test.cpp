#include "core/common/contract.h"

#include <gtest/gtest.h>

namespace imagepro {
namespace {

#if defined(NDEBUG) && !defined(IMAGEPRO_CONTRACTS)
TEST(Contract, FailedCheckAbortsWithItsMessage) {
  GTEST_SKIP() << "the checks compile to nothing here (a release build without -DIMAGEPRO_CONTRACTS=ON)";
}
#else
int checkedIndex(int i, int n) {
  IMAGEPRO_EXPECTS(i >= 0 && i < n, "index inside the buffer");
  return i;
}

TEST(Contract, FailedCheckAbortsWithItsMessage) {
  EXPECT_EQ(checkedIndex(2, 3), 2);
  EXPECT_DEATH(checkedIndex(3, 3), "precondition failed: index inside the buffer \\(i >= 0 && i < n\\)");
}
#endif

}  // namespace
}  // namespace imagepro
