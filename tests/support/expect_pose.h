#pragma once
// Each of a pose's six parameters within `tol` of the wanted one.
#include <gtest/gtest.h>

#include "core/common/geometry.h"

namespace imagepro::test {

inline void expectPose(const Pose& got, const Pose& want, double tol = 1e-9) {
  EXPECT_NEAR(got.rx_deg, want.rx_deg, tol);
  EXPECT_NEAR(got.ry_deg, want.ry_deg, tol);
  EXPECT_NEAR(got.rz_deg, want.rz_deg, tol);
  EXPECT_NEAR(got.tx_mm, want.tx_mm, tol);
  EXPECT_NEAR(got.ty_mm, want.ty_mm, tol);
  EXPECT_NEAR(got.tz_mm, want.tz_mm, tol);
}

}  // namespace imagepro::test
