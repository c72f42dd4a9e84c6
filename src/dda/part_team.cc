/**
 * @file
 * The threads and ranks of the D-ILU's subdomains (part_team.h).
 */
#include "part_team.h"

#include "thread_pair.h"
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace rockdda::dda::internal
{
  std::vector<int>
  level_parts(const int                               n,
              const std::vector<std::pair<int, int>> &pairs,
              const int                               parts)
  {
    std::vector<int> start(n + 1, 0), adjacent(2 * pairs.size());
    for (const auto &pr : pairs)
      {
        ++start[pr.first + 1];
        ++start[pr.second + 1];
      }
    for (int i = 0; i < n; ++i)
      start[i + 1] += start[i];
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (const auto &pr : pairs)
      {
        adjacent[fill[pr.first]++]  = pr.second;
        adjacent[fill[pr.second]++] = pr.first;
      }
    std::vector<int> level(n, -1), probe(n, -1), queue;
    queue.reserve(n);
    const auto bfs = [&](const int root, std::vector<int> &depth, int base) {
      queue.clear();
      queue.push_back(root);
      depth[root] = base;
      for (std::size_t h = 0; h < queue.size(); ++h)
        {
          const int u = queue[h];
          for (int a = start[u]; a < start[u + 1]; ++a)
            if (depth[adjacent[a]] < 0)
              {
                depth[adjacent[a]] = depth[u] + 1;
                queue.push_back(adjacent[a]);
              }
        }
      return depth[queue.back()];
    };
    int n_levels = 0;
    for (int s = 0; s < n; ++s)
      if (level[s] < 0)
        {
          bfs(s, probe, 0);
          n_levels = bfs(queue.back(), level, n_levels) + 1;
        }
    std::vector<long long> count(n_levels, 0);
    for (int i = 0; i < n; ++i)
      ++count[level[i]];
    // The separating levels, ascending; a block's subdomain is the number
    // of them below its level.
    std::vector<int> split;
    long long        below = 0;
    int              l     = 0;
    for (int d = 1; d < parts; ++d)
      {
        // Levels from l on (two above the previous split): the first
        // that minimises |parts (2 below + count) - 2 d n|.
        int       best_level = -1;
        long long best       = 0;
        long long b          = below;
        for (int m = l; m < n_levels; b += count[m], ++m)
          {
            const long long miss
              = std::llabs(parts * (2 * b + count[m]) - 2LL * d * n);
            if (best_level < 0 || miss < best)
              {
                best       = miss;
                best_level = m;
              }
          }
        if (best_level < 0)
          break;
        split.push_back(best_level);
        for (; l < best_level + 2 && l < n_levels; ++l)
          below += count[l];
      }
    std::vector<int> part_of_level(n_levels, 0);
    for (int m = 0, d = 0; m < n_levels; ++m)
      {
        const bool separates
          = d < static_cast<int>(split.size()) && split[d] == m;
        part_of_level[m] = separates ? parts : d;
        if (separates)
          ++d;
      }
    std::vector<int> part(n);
    for (int i = 0; i < n; ++i)
      part[i] = part_of_level[level[i]];
    return part;
  }



  PairTeam::PairTeam(ThreadPair &pair, const int parts)
      : pair(pair)
      , parts(parts)
  {
    if (parts < 1 || parts > 2)
      throw std::invalid_argument("PairTeam: 1 or 2 subdomains");
  }



  int
  PairTeam::n_parts() const
  {
    return parts;
  }



  bool
  PairTeam::computes(const int) const
  {
    return true;
  }



  void
  PairTeam::run(const std::function<void(int)> &f)
  {
    if (parts == 1)
      {
        f(0);
        return;
      }
    auto g = [&f](const int d) { f(d); };
    pair.run(g);
  }



  void
  PairTeam::share(double *, const std::size_t)
  {}



  void
  PairTeam::share_rows(double *, const std::vector<int> &, const int)
  {}



  bool
  PairTeam::same_everywhere(const Eigen::VectorXd &)
  {
    return true;
  }



  RankTeam::RankTeam(const MPI_Comm comm)
      : comm(comm)
  {
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    counts.resize(size);
    offsets.resize(size);
  }



  int
  RankTeam::n_parts() const
  {
    return size;
  }



  bool
  RankTeam::computes(const int d) const
  {
    return d == rank;
  }



  void
  RankTeam::run(const std::function<void(int)> &f)
  {
    f(rank);
  }



  void
  RankTeam::share(double *data, const std::size_t m)
  {
    MPI_Allgather(MPI_IN_PLACE,
                  0,
                  MPI_DATATYPE_NULL,
                  data,
                  static_cast<int>(m),
                  MPI_DOUBLE,
                  comm);
  }



  void
  RankTeam::share_rows(double                 *data,
                       const std::vector<int> &first,
                       const int               width)
  {
    for (int d = 0; d < size; ++d)
      {
        offsets[d] = width * first[d];
        counts[d]  = width * (first[d + 1] - first[d]);
      }
    MPI_Allgatherv(MPI_IN_PLACE,
                   0,
                   MPI_DATATYPE_NULL,
                   data,
                   counts.data(),
                   offsets.data(),
                   MPI_DOUBLE,
                   comm);
  }



  bool
  RankTeam::same_everywhere(const Eigen::VectorXd &v)
  {
    return same_on_every_rank(v, comm);
  }



  bool
  same_on_every_rank(const Eigen::VectorXd &v, const MPI_Comm comm)
  {
    // FNV-1a over the bits of the values: equal on every rank exactly when
    // the ranks hold the same values (up to a hash collision).
    std::uint64_t h = 1469598103934665603ull;
    for (Eigen::Index i = 0; i < v.size(); ++i)
      {
        std::uint64_t bits;
        std::memcpy(&bits, &v[i], sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
      }
    std::uint64_t low = h, high = h;
    MPI_Allreduce(MPI_IN_PLACE, &low, 1, MPI_UINT64_T, MPI_MIN, comm);
    MPI_Allreduce(MPI_IN_PLACE, &high, 1, MPI_UINT64_T, MPI_MAX, comm);
    return low == high;
  }
} // namespace rockdda::dda::internal
