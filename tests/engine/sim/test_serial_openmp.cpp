// The guard that keeps CHOLMOD's per-supernode OpenMP teams from forming (serial_openmp.hpp).
#include <gtest/gtest.h>
#include <omp.h>

#include <thread>
#include <vector>

#include "serial_openmp.hpp"
#include "sutura/engine/sim/linear_solver.hpp"

namespace sutura::engine {
namespace {

// The size of the team a region asking for two threads gets, as CHOLMOD's `num_threads` clause
// asks for a fixed count regardless of omp_set_num_threads.
int team_size_asking_for_two() {
  int size = 0;
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    size = omp_get_num_threads();
  }
  return size;
}

TEST(SerialOpenMp, RegionsWithAFixedThreadCountRunOnOneThreadWhileAGuardIsAlive) {
  const int before = omp_get_max_active_levels();
  ASSERT_GE(before, 1) << "OpenMP parallel regions are off in this test process";
  {
    const detail::SerialOpenMp serial;
    EXPECT_EQ(omp_get_max_active_levels(), 0);
    EXPECT_EQ(team_size_asking_for_two(), 1);
  }
  EXPECT_EQ(omp_get_max_active_levels(), before);
}

TEST(SerialOpenMp, NestedGuardsRestoreTheSettingWhenTheOutermostEnds) {
  const int before = omp_get_max_active_levels();
  {
    const detail::SerialOpenMp outer;
    { const detail::SerialOpenMp inner; }
    EXPECT_EQ(omp_get_max_active_levels(), 0) << "the inner guard ended the outer one's effect";
  }
  EXPECT_EQ(omp_get_max_active_levels(), before);
}

TEST(SerialOpenMp, AGuardOnOneThreadLeavesOtherThreadsParallel) {
  const detail::SerialOpenMp serial;
  int levels = -1, team = -1, levels_in_own_guard = -1, team_in_own_guard = -1;
  std::thread other([&] {
    levels = omp_get_max_active_levels();
    team = team_size_asking_for_two();
    const detail::SerialOpenMp own;
    levels_in_own_guard = omp_get_max_active_levels();
    team_in_own_guard = team_size_asking_for_two();
  });
  other.join();
  EXPECT_GE(levels, 1);
  EXPECT_EQ(team, 2);
  EXPECT_EQ(levels_in_own_guard, 0);
  EXPECT_EQ(team_in_own_guard, 1);
  EXPECT_EQ(team_size_asking_for_two(), 1);
}

TEST(SerialOpenMp, CholmodFactorisationLeavesTheSettingAsItWas) {
  const int before = omp_get_max_active_levels();
  Eigen::SparseMatrix<double> A(300, 300);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < 300; ++i) {
    t.emplace_back(i, i, 4.0);
    if (i + 1 < 300) t.emplace_back(i, i + 1, -1.0), t.emplace_back(i + 1, i, -1.0);
  }
  A.setFromTriplets(t.begin(), t.end());
  auto solver = make_linear_solver(LinearSolverKind::Cholmod);
  ASSERT_TRUE(solver->factorize(A));
  EXPECT_EQ(omp_get_max_active_levels(), before);
  A.coeffRef(0, 0) = -1.0;  // indefinite: the failed Cholesky path must restore it too
  EXPECT_FALSE(solver->factorize_definite(A));
  EXPECT_EQ(omp_get_max_active_levels(), before);
}

}  // namespace
}  // namespace sutura::engine
