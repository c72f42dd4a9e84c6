/**
 * @file
 * Block sparse Cholesky factorisation (internal::BlockCholeskyOf).
 */
#include "block_cholesky.h"

#include <Eigen/Cholesky>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

#include <algorithm>

namespace rockdda::dda::internal
{
  template <int dofs>
  void
  BlockCholeskyOf<dofs>::analyse(const Matrix &K)
  {
    if (K.n_blocks() == n && K.pairs == pairs)
      return;
    n     = K.n_blocks();
    pairs = K.pairs;

    // Minimum-degree ordering of the block graph: Eigen's AMD gives the
    // old block of each new position.
    {
      std::vector<Eigen::Triplet<double, int>> entries;
      entries.reserve(n + 2 * pairs.size());
      for (int b = 0; b < n; ++b)
        entries.emplace_back(b, b, 1.);
      for (const auto &[a, b] : pairs)
        {
          entries.emplace_back(a, b, 1.);
          entries.emplace_back(b, a, 1.);
        }
      Eigen::SparseMatrix<double, Eigen::ColMajor, int> graph(n, n);
      graph.setFromTriplets(entries.begin(), entries.end());
      Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order;
      Eigen::AMDOrdering<int>{}(graph, order);
      old_of.assign(order.indices().data(), order.indices().data() + n);
    }
    new_of.assign(n, 0);
    for (int k = 0; k < n; ++k)
      new_of[old_of[k]] = k;

    // Rows of each column of L: the column's own couplings below the
    // diagonal and those its children in the elimination tree pass on.
    std::vector<std::vector<int>> below(n), children(n);
    for (const auto &[a, b] : pairs)
      {
        const int i = new_of[a], j = new_of[b];
        below[std::min(i, j)].push_back(std::max(i, j));
      }
    start.assign(n + 1, 0);
    row.clear();
    std::vector<int> merged;
    for (int k = 0; k < n; ++k)
      {
        // Column k starts at the end of column k - 1 (set before its
        // children, of which k - 1 may be one, are read).
        start[k]   = static_cast<int>(row.size());
        auto &rows = below[k];
        for (const int c : children[k])
          {
            const int s = start[c] + 1, e = start[c + 1];
            rows.insert(rows.end(), row.begin() + s, row.begin() + e);
          }
        std::sort(rows.begin(), rows.end());
        rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
        rows.erase(std::remove(rows.begin(), rows.end(), k), rows.end());
        row.push_back(k);
        row.insert(row.end(), rows.begin(), rows.end());
        if (!rows.empty())
          children[rows.front()].push_back(k);
        std::vector<int>().swap(rows);
      }
    start[n] = static_cast<int>(row.size());
    factor.assign(row.size(), Dense::Zero());

    // Position of block (i, j), i >= j, in L.
    const auto position = [this](const int i, const int j) {
      if (i == j)
        return start[j];
      const auto first = row.begin() + start[j] + 1,
                 last  = row.begin() + start[j + 1];
      return static_cast<int>(std::lower_bound(first, last, i) - row.begin());
    };
    pair_target.resize(pairs.size());
    pair_transposed.resize(pairs.size());
    for (std::size_t p = 0; p < pairs.size(); ++p)
      {
        // K_ab (a < b) is block (new a, new b) of the reordered matrix;
        // L stores the lower one.
        const int i = new_of[pairs[p].first], j = new_of[pairs[p].second];
        pair_transposed[p] = i < j;
        pair_target[p]     = i > j ? position(i, j) : position(j, i);
      }
    update_start.assign(n + 1, 0);
    update.clear();
    for (int k = 0; k < n; ++k)
      {
        update_start[k] = static_cast<int>(update.size());
        for (int a = start[k] + 1; a < start[k + 1]; ++a)
          for (int b = a; b < start[k + 1]; ++b)
            update.push_back(position(row[b], row[a]));
      }
    update_start[n] = static_cast<int>(update.size());
  }



  template <int dofs>
  bool
  BlockCholeskyOf<dofs>::factorize(const Matrix &K)
  {
    for (auto &f : factor)
      f.setZero();
    for (int b = 0; b < n; ++b)
      factor[start[new_of[b]]] = K.diag[b];
    for (std::size_t p = 0; p < pairs.size(); ++p)
      if (pair_transposed[p])
        factor[pair_target[p]] = K.off[p].transpose();
      else
        factor[pair_target[p]] = K.off[p];

    for (int k = 0; k < n; ++k)
      {
        Dense &L = factor[start[k]];
        if (!L.allFinite())
          return false;
        const Eigen::LLT<Dense, Eigen::Lower> llt(L);
        if (llt.info() != Eigen::Success)
          return false;
        // The column stores L_kk^-1 (lower): the blocks below and the
        // solves then take dense products only.
        const Dense &C = llt.matrixLLT();
        L.setZero();
        for (int c = 0; c < dofs; ++c)
          {
            L(c, c) = 1. / C(c, c);
            for (int i = c + 1; i < dofs; ++i)
              {
                double v = 0.;
                for (int j = c; j < i; ++j)
                  v -= C(i, j) * L(j, c);
                L(i, c) = v / C(i, i);
              }
          }
        if (!L.allFinite() || !(L.diagonal().array() > 0.).all())
          return false;
        // L_ik = K_ik L_kk^-T.
        const int s = start[k] + 1, e = start[k + 1];
        for (int m = s; m < e; ++m)
          factor[m] = (factor[m] * L.transpose()).eval();
        int u = update_start[k];
        for (int a = s; a < e; ++a)
          for (int b = a; b < e; ++b)
            factor[update[u++]].noalias() -= factor[b] * factor[a].transpose();
      }
    return true;
  }



  template <int dofs>
  void
  BlockCholeskyOf<dofs>::solve(const Eigen::VectorXd &f,
                               Eigen::VectorXd       &x) const
  {
    y.resize(dofs * n);
    for (int b = 0; b < n; ++b)
      y.template segment<dofs>(dofs * new_of[b])
        = f.template segment<dofs>(dofs * b);
    Vector v;
    for (int k = 0; k < n; ++k)
      {
        v.noalias() = factor[start[k]] * y.template segment<dofs>(dofs * k);
        y.template segment<dofs>(dofs * k) = v;
        for (int m = start[k] + 1; m < start[k + 1]; ++m)
          y.template segment<dofs>(dofs * row[m]).noalias() -= factor[m] * v;
      }
    for (int k = n - 1; k >= 0; --k)
      {
        v = y.template segment<dofs>(dofs * k);
        for (int m = start[k] + 1; m < start[k + 1]; ++m)
          v.noalias()
            -= factor[m].transpose() * y.template segment<dofs>(dofs * row[m]);
        y.template segment<dofs>(dofs * k).noalias()
          = factor[start[k]].transpose() * v;
      }
    x.resize(dofs * n);
    for (int b = 0; b < n; ++b)
      x.template segment<dofs>(dofs * b)
        = y.template segment<dofs>(dofs * new_of[b]);
  }



  template class BlockCholeskyOf<6>;
  template class BlockCholeskyOf<12>;
} // namespace rockdda::dda::internal
