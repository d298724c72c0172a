#include "blas_threads.hpp"

#include <dlfcn.h>

namespace sutura::engine::detail {
namespace {

using GetThreads = int (*)();
using SetThreads = void (*)(int);

struct OpenBlas {
  GetThreads get = nullptr;
  SetThreads set = nullptr;
  OpenBlas() {
    get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
    set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
    if (get == nullptr || set == nullptr) get = nullptr, set = nullptr;
  }
};

const OpenBlas& openblas() {
  static const OpenBlas instance;
  return instance;
}

}  // namespace

int blas_thread_count() {
  const OpenBlas& blas = openblas();
  return blas.get != nullptr ? blas.get() : 1;
}

void set_blas_thread_count(int n) {
  const OpenBlas& blas = openblas();
  if (blas.set != nullptr) blas.set(n);
}

SingleThreadedBlas::SingleThreadedBlas() {
  const OpenBlas& blas = openblas();
  if (blas.get == nullptr) return;
  const int n = blas.get();
  if (n <= 1) return;
  previous_ = n;
  blas.set(1);
}

SingleThreadedBlas::~SingleThreadedBlas() {
  if (previous_ > 0) openblas().set(previous_);
}

}  // namespace sutura::engine::detail
