#include "single_precision_factor.hpp"

#include <omp.h>

#include <algorithm>
#include <utility>

#include "sutura/engine/errors.hpp"

namespace sutura::engine::detail {

namespace {

using Vec = Eigen::VectorXf;
// A supernode's block: nsrow x nscol, column-major with leading dimension nsrow; its top
// nscol x nscol square is lower triangular (the diagonal block), the rows below it are the
// off-diagonal rows, listed in L.s.
using Block = Eigen::Map<const Eigen::MatrixXf, 0, Eigen::OuterStride<>>;

// CHOLMOD's factor arrays are int for the int interface the engine uses (Eigen's
// CholmodSupernodalLLT with int indices).
const int* ints(const void* p) { return static_cast<const int*>(p); }

// Below this many factor entries (about 1k elements) a second thread costs more than it saves.
constexpr std::size_t kParallelEntries = 200000;
// The split stops when the heavier half holds at most this share of the halves' entries.
constexpr double kBalance = 0.55;
// At most this many supernodes are moved from the halves to the top while balancing.
constexpr int kMaxTopSupernodes = 1000;

}  // namespace

void SinglePrecisionFactor::assign(const cholmod_factor& L) {
  if (!L.is_super || !L.is_ll || L.xtype != CHOLMOD_REAL || L.itype != CHOLMOD_INT)
    throw InvalidArgument("single-precision factor: needs a real supernodal LL^T factor");
  const auto* x = static_cast<const double*>(L.x);
  values_.assign(x, x + L.xsize);
  split(L);
}

// The supernodal elimination tree: the parent of a supernode is the one holding its first
// off-diagonal row (all its off-diagonal rows belong to ancestors). Starting from the roots,
// the heaviest subtree of the frontier is moved to the top, its children taking its place,
// until the frontier's subtrees fall into two halves of about equal weight (largest first,
// each into the lighter half). With a nested-dissection ordering (CHOLMOD's METIS) that moves
// the top separators.
void SinglePrecisionFactor::split(const cholmod_factor& L) {
  const auto n = static_cast<int>(L.n);
  const auto nsuper = static_cast<int>(L.nsuper);
  const int* super = ints(L.super);
  const int* row_start = ints(L.pi);
  const int* rows = ints(L.s);
  std::vector<int> column_super(static_cast<std::size_t>(n));
  for (int s = 0; s < nsuper; ++s)
    for (int k = super[s]; k < super[s + 1]; ++k) column_super[k] = s;
  std::vector<int> parent(static_cast<std::size_t>(nsuper), -1);
  std::vector<double> weight(static_cast<std::size_t>(nsuper), 0.0);  // entries in the subtree
  std::vector<int> child_count(static_cast<std::size_t>(nsuper) + 1, 0);
  bool postordered = true;
  for (int s = 0; s < nsuper; ++s) {
    const int ncol = super[s + 1] - super[s];
    const int nrow = row_start[s + 1] - row_start[s];
    weight[s] += static_cast<double>(nrow) * ncol;
    if (nrow > ncol) {
      const int* first = rows + row_start[s] + ncol;
      parent[s] = column_super[*std::min_element(first, rows + row_start[s + 1])];
      if (parent[s] <= s) postordered = false;
    }
  }
  halves_[0].clear();
  halves_[1].clear();
  top_.clear();
  // Ancestors after descendants is what the solves' order relies on; CHOLMOD's supernodes are
  // always so numbered. Should a factor not be, everything is top: one thread, CHOLMOD's order.
  if (!postordered) {
    for (int s = 0; s < nsuper; ++s) top_.push_back(s);
  } else {
    for (int s = 0; s < nsuper; ++s)
      if (parent[s] >= 0) weight[parent[s]] += weight[s], ++child_count[parent[s] + 1];
    for (int s = 0; s < nsuper; ++s) child_count[s + 1] += child_count[s];
    std::vector<int> children(static_cast<std::size_t>(child_count[nsuper]));
    {
      std::vector<int> next(child_count.begin(), child_count.end() - 1);
      for (int s = 0; s < nsuper; ++s)
        if (parent[s] >= 0) children[next[parent[s]]++] = s;
    }
    constexpr int kTop = -1;
    std::vector<int> group(static_cast<std::size_t>(nsuper), -2);  // -2: inherits its parent's
    std::vector<int> frontier;
    for (int s = 0; s < nsuper; ++s)
      if (parent[s] < 0) frontier.push_back(s);
    const auto heavier_first = [&](int a, int b) {
      return weight[a] != weight[b] ? weight[a] > weight[b] : a < b;
    };
    std::vector<int> bin_of;
    for (int moved = 0;; ++moved) {
      std::sort(frontier.begin(), frontier.end(), heavier_first);
      double bins[2] = {0.0, 0.0};
      bin_of.assign(frontier.size(), 0);
      for (std::size_t i = 0; i < frontier.size(); ++i) {
        const int b = bins[1] < bins[0] ? 1 : 0;
        bin_of[i] = b;
        bins[b] += weight[frontier[i]];
      }
      const double total = bins[0] + bins[1];
      const int heaviest = frontier.empty() ? -1 : frontier.front();
      if (total == 0.0 || std::max(bins[0], bins[1]) <= kBalance * total ||
          moved == kMaxTopSupernodes || child_count[heaviest] == child_count[heaviest + 1])
        break;
      group[heaviest] = kTop;
      frontier.erase(frontier.begin());
      frontier.insert(frontier.end(), children.begin() + child_count[heaviest],
                      children.begin() + child_count[heaviest + 1]);
    }
    for (std::size_t i = 0; i < frontier.size(); ++i) group[frontier[i]] = bin_of[i];
    for (int s = nsuper - 1; s >= 0; --s)
      if (group[s] == -2) group[s] = parent[s] >= 0 ? group[parent[s]] : kTop;
    for (int s = 0; s < nsuper; ++s) (group[s] == kTop ? top_ : halves_[group[s]]).push_back(s);
  }
  is_top_row_.assign(static_cast<std::size_t>(n), 0);
  top_columns_.clear();
  for (const int s : top_)
    for (int k = super[s]; k < super[s + 1]; ++k) is_top_row_[k] = 1, top_columns_.push_back(k);
}

// Forward, L y = P b, over `supernodes` in increasing order: the diagonal block's triangular
// solve, then the off-diagonal rows' products subtracted from the rows they stand for; a half
// (half >= 0) collects the products for top rows in its spill buffer instead.
void SinglePrecisionFactor::forward(const cholmod_factor& L, const std::vector<int>& supernodes,
                                    int half) {
  const int* super = ints(L.super);
  const int* row_start = ints(L.pi);
  const int* value_start = ints(L.px);
  const int* rows = ints(L.s);
  float* spill = half >= 0 ? spill_[half].data() : nullptr;
  std::vector<float>& work = work_[half >= 0 ? half : 0];
  for (const int s : supernodes) {
    const int k1 = super[s], ncol = super[s + 1] - k1;
    const int nrow = row_start[s + 1] - row_start[s], below = nrow - ncol;
    const float* block = values_.data() + value_start[s];
    Eigen::Map<Vec> ys(y_.data() + k1, ncol);
    Block(block, ncol, ncol, Eigen::OuterStride<>(nrow))
        .triangularView<Eigen::Lower>()
        .solveInPlace(ys);
    if (below == 0) continue;
    Eigen::Map<Vec> e(work.data(), below);
    e.noalias() = Block(block + ncol, below, ncol, Eigen::OuterStride<>(nrow)) * ys;
    const int* r = rows + row_start[s] + ncol;
    if (spill == nullptr) {
      for (int i = 0; i < below; ++i) y_[r[i]] -= work[i];
    } else {
      for (int i = 0; i < below; ++i) {
        if (is_top_row_[r[i]]) spill[r[i]] += work[i];
        else y_[r[i]] -= work[i];
      }
    }
  }
}

// Backward, L^T z = y, over `supernodes` in decreasing order: the off-diagonal rows'
// contributions gathered, then the transposed diagonal block's triangular solve.
void SinglePrecisionFactor::backward(const cholmod_factor& L, const std::vector<int>& supernodes,
                                     int half) {
  const int* super = ints(L.super);
  const int* row_start = ints(L.pi);
  const int* value_start = ints(L.px);
  const int* rows = ints(L.s);
  std::vector<float>& work = work_[half >= 0 ? half : 0];
  for (auto it = supernodes.rbegin(); it != supernodes.rend(); ++it) {
    const int s = *it;
    const int k1 = super[s], ncol = super[s + 1] - k1;
    const int nrow = row_start[s + 1] - row_start[s], below = nrow - ncol;
    const float* block = values_.data() + value_start[s];
    Eigen::Map<Vec> ys(y_.data() + k1, ncol);
    if (below > 0) {
      const int* r = rows + row_start[s] + ncol;
      for (int i = 0; i < below; ++i) work[i] = y_[r[i]];
      const Eigen::Map<const Vec> e(work.data(), below);
      ys.noalias() -= Block(block + ncol, below, ncol, Eigen::OuterStride<>(nrow)).transpose() * e;
    }
    Block(block, ncol, ncol, Eigen::OuterStride<>(nrow))
        .transpose()
        .triangularView<Eigen::Upper>()
        .solveInPlace(ys);
  }
}

void SinglePrecisionFactor::solve(const cholmod_factor& L, const Eigen::VectorXd& b,
                                  Eigen::VectorXd& x) {
  const auto n = static_cast<Eigen::Index>(L.n);
  if (b.size() != n) throw InvalidArgument("single-precision factor: right-hand side size");
  if (values_.size() != L.xsize || is_top_row_.size() != L.n)
    throw InvalidArgument("single-precision factor: assign() the factor before solving");
  const int* perm = ints(L.Perm);
  y_.resize(static_cast<std::size_t>(n));
  // No permutation stored: the natural ordering.
  for (Eigen::Index k = 0; k < n; ++k) y_[k] = static_cast<float>(b[perm ? perm[k] : k]);
  for (int h = 0; h < 2; ++h) {
    work_[h].resize(L.maxesize);
    spill_[h].resize(static_cast<std::size_t>(n));
    for (const int t : top_columns_) spill_[h][t] = 0.0f;
  }
  const bool parallel = omp_get_max_threads() > 1 && values_.size() >= kParallelEntries &&
                        !halves_[0].empty() && !halves_[1].empty();
#pragma omp parallel for num_threads(2) schedule(static, 1) if (parallel)
  for (int h = 0; h < 2; ++h) forward(L, halves_[h], h);
  for (int h = 0; h < 2; ++h)
    for (const int t : top_columns_) y_[t] -= spill_[h][t];
  forward(L, top_, -1);
  backward(L, top_, -1);
#pragma omp parallel for num_threads(2) schedule(static, 1) if (parallel)
  for (int h = 0; h < 2; ++h) backward(L, halves_[h], h);
  x.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) x[perm ? perm[k] : k] = static_cast<double>(y_[k]);
}

}  // namespace sutura::engine::detail
