// The solver tuning's range checks (tuning.h).
#include "geofair/fairing.h"
#include "geofair/tuning.h"
#include "meshes.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace geofair {
namespace {

TEST(SolverTuning, DefaultsAreInRange) { EXPECT_NO_THROW(validate_tuning(SolverTuning{})); }

TEST(SolverTuning, AFieldOutOfRangeIsNamed) {
  SolverTuning t;
  t.newton.patience = 0;
  try {
    validate_tuning(t);
    FAIL() << "no exception";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("tuning.newton.patience"), std::string::npos) << e.what();
  }
  t = SolverTuning{};
  t.tangential.max_stretch = 1.0;  // the interval is open
  EXPECT_THROW(validate_tuning(t), InvalidInputError);
  t = SolverTuning{};
  t.schedule.time_limit_base = std::nan("");
  EXPECT_THROW(validate_tuning(t), InvalidInputError);
}

TEST(SolverTuning, FairRejectsBadTuningBeforeSolving) {
  const testing::Mesh m = testing::planar_grid(6);
  std::vector<bool> free(m.V.rows(), false);
  for (int j = 1; j < 6; ++j)
    for (int i = 1; i < 6; ++i) free[j * 7 + i] = true;
  FairingOptions options;
  options.tuning.multigrid.base_reduction = 0.0;
  EXPECT_THROW(fair(m.V, m.F, free, nullptr, options), InvalidInputError);
}

}  // namespace
}  // namespace geofair
