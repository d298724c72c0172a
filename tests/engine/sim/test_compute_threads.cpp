// The engine's compute thread count (OpenMP and OpenBLAS).
#include <gtest/gtest.h>

#include "sutura/engine/blas_kernels.hpp"
#include "sutura/engine/compute_threads.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {
namespace {

TEST(ComputeThreads, SetsBothCountsAndRejectsZero) {
  const ComputeThreads before = compute_threads();
  EXPECT_GE(before.openmp, 1);
  EXPECT_GE(before.blas, 1);
  set_compute_threads(1);
  EXPECT_EQ(compute_threads().openmp, 1);
  EXPECT_EQ(compute_threads().blas, 1);
  set_compute_threads(3);
  EXPECT_EQ(compute_threads().openmp, 3);
  if (blas_kernels_in_use().rfind("OpenBLAS", 0) == 0) {
    EXPECT_EQ(compute_threads().blas, 3);
  }
  EXPECT_THROW(set_compute_threads(0), InvalidArgument);
  set_compute_threads(before.openmp);
}

}  // namespace
}  // namespace sutura::engine
