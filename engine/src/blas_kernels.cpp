#include "sutura/engine/blas_kernels.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>

namespace sutura::engine {

namespace {

// The kernels OpenBLAS chose, or nullptr without OpenBLAS. Looked up at run time like the
// thread control in sim/blas_threads.cpp: the engine links against whatever BLAS CHOLMOD uses.
const char* openblas_corename() {
  using CoreName = char* (*)();
  const auto corename = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  return corename == nullptr ? nullptr : corename();
}

}  // namespace

std::string blas_kernels_in_use() {
  const char* name = openblas_corename();
  return name == nullptr ? "unknown" : std::string("OpenBLAS ") + name;
}

const char* better_blas_coretype() {
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return nullptr;
  const char* chosen = openblas_corename();
  if (chosen == nullptr || strcasecmp(chosen, "prescott") != 0) return nullptr;
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512cd"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
  return nullptr;
}

}  // namespace sutura::engine
