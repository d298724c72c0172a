#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "sutura/engine/blas_kernels.hpp"

using namespace sutura::engine;

TEST(BlasKernels, NamesTheLoadedBlas) {
  const std::string name = blas_kernels_in_use();
  // The project links CHOLMOD against the system BLAS: OpenBLAS where scripts/ installed it.
  if (name != "unknown") {
    ASSERT_EQ(name.rfind("OpenBLAS ", 0), 0u) << name;
    EXPECT_GT(name.size(), std::string("OpenBLAS ").size());
  }
}

TEST(BlasKernels, OnlyTheGenericFallbackIsReplaced) {
  const char* better = better_blas_coretype();
  if (better == nullptr) return;  // OpenBLAS knew this CPU (or another BLAS): nothing to check
  EXPECT_EQ(blas_kernels_in_use(), "OpenBLAS Prescott");
  EXPECT_TRUE(std::string(better) == "SkylakeX" || std::string(better) == "Haswell") << better;
}

TEST(BlasKernels, AChoiceInTheEnvironmentIsKept) {
  const char* before = std::getenv("OPENBLAS_CORETYPE");
  const std::string saved = before ? before : "";
  setenv("OPENBLAS_CORETYPE", "Prescott", 1);
  EXPECT_EQ(better_blas_coretype(), nullptr);
  if (before) setenv("OPENBLAS_CORETYPE", saved.c_str(), 1);
  else unsetenv("OPENBLAS_CORETYPE");
}
