#pragma once
// Runs OpenMP parallel regions on the encountering thread alone while alive (private to
// engine/src/sim).
//
// Why: Debian's CHOLMOD (SuiteSparse 5.12) opens an OpenMP team for the small copy and scatter
// loops of every supernode of its numeric factorisation (zero the supernode, build its row map,
// copy A in, assemble each descendant's update): thousands of teams per factorisation, with a
// thread count fixed when CHOLMOD was compiled (a `num_threads` clause, which overrides
// omp_set_num_threads). On a 2-core machine every team wakes threads that then compete with
// OpenBLAS's own threads for the cores, and the hand-over costs far more than the loops save:
// one Newton iteration at 20k elements took 420 ms with the teams and 280 ms without them
// (docs/performance.md). The loops only copy, so the factor is bit-identical either way.
//
// How: max-active-levels = 0 makes every region the thread starts inactive (one thread); it is
// the only OpenMP setting that a `num_threads` clause does not override. Like the thread count
// it belongs to the calling thread (OpenMP 5.0; libgomp 12), so other threads are not affected.
// Guards nest.

namespace sutura::engine::detail {

class SerialOpenMp {
 public:
  SerialOpenMp();
  ~SerialOpenMp();
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

 private:
  int saved_levels_;  ///< the calling thread's max-active-levels before the guard
};

}  // namespace sutura::engine::detail
