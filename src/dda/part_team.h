/**
 * @file
 * Internal to the dda subsystem: where the parts of the block D-ILU's
 * sweeps run. The D-ILU orders the blocks as P subdomains that do not
 * couple and a separator eliminated last (linear_solver.cc); each sweep
 * runs the subdomains, then shares what each wrote for the separator,
 * then does the separator. The same arithmetic runs on the threads of one
 * process (PairTeam) or on the ranks of an MPI communicator (RankTeam,
 * subdomain d on rank d; every rank holds the replicated matrix and does
 * the separator), so a run on P ranks takes the steps of the serial run
 * with the same P subdomains, bit for bit.
 */
#ifndef ROCKDDA_DDA_PART_TEAM_H
#define ROCKDDA_DDA_PART_TEAM_H

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <mpi.h>
#include <utility>
#include <vector>

namespace rockdda::dda::internal
{
  class ThreadPair;

  /**
   * @p parts subdomains and a separator of the block graph (the pairs):
   * BFS level structure from a pseudo-peripheral block of each connected
   * component (levels numbered on across components). Edges join equal
   * or neighbouring levels only, so a level separates the blocks below it
   * from those above: parts - 1 levels, no two adjacent, each chosen in
   * turn where the blocks below its middle come nearest to d n / parts,
   * split the blocks into subdomains 0 .. parts - 1 that do not couple;
   * those levels are the separator, part @p parts (George & Liu 1981,
   * Computer Solution of Large Sparse Positive Definite Systems, ch. 4
   * and 8). For two parts the level balances the blocks below and above
   * it. A graph with too few levels leaves the last subdomains empty.
   */
  std::vector<int>
  level_parts(const int                               n,
              const std::vector<std::pair<int, int>> &pairs,
              const int                               parts);

  /// Whether @p v is the same, bit for bit, on every rank of @p comm (a
  /// hash of its bits compared; collective).
  bool
  same_on_every_rank(const Eigen::VectorXd &v, const MPI_Comm comm);

  /**
   * Runs the subdomains of a partitioned sweep and shares their results.
   * share() and share_rows() are collective over the processes of the team.
   */
  class PartTeam
  {
  public:
    virtual ~PartTeam() = default;

    /// Number of subdomains.
    virtual int
    n_parts() const = 0;

    /// Whether this process computes subdomain @p d.
    virtual bool
    computes(const int d) const = 0;

    /// Run f(d) for every subdomain d this process computes.
    virtual void
    run(const std::function<void(int)> &f)
      = 0;

    /// @p data holds n_parts() slices of @p m values, slice d written by
    /// subdomain d: afterwards every process holds every slice.
    virtual void
    share(double *data, const std::size_t m)
      = 0;

    /// Entries [width first[d], width first[d + 1]) of @p data written by
    /// subdomain d: afterwards every process holds all of them.
    virtual void
    share_rows(double *data, const std::vector<int> &first, const int width)
      = 0;

    /**
     * @p parts subdomains and a separator of the block graph (the pairs):
     * BFS level structure from a pseudo-peripheral block of each connected
     * component (levels numbered on across components). Edges join equal
     * or neighbouring levels only, so a level separates the blocks below it
     * from those above: parts - 1 levels, no two adjacent, each chosen in
     * turn where the blocks below its middle come nearest to d n / parts,
     * split the blocks into subdomains 0 .. parts - 1 that do not couple;
     * those levels are the separator, part @p parts (George & Liu 1981,
     * Computer Solution of Large Sparse Positive Definite Systems, ch. 4
     * and 8). For two parts the level balances the blocks below and above
     * it. A graph with too few levels leaves the last subdomains empty.
     */
    std::vector<int>
    level_parts(const int                               n,
                const std::vector<std::pair<int, int>> &pairs,
                const int                               parts);

    /// Whether @p v is the same, bit for bit, on every process.
    virtual bool
    same_everywhere(const Eigen::VectorXd &v)
      = 0;
  };

  /// The subdomains on one or two threads of this process (a ThreadPair):
  /// nothing to share.
  class PairTeam : public PartTeam
  {
  public:
    /// @p parts subdomains (1 or 2) on the threads of @p pair.
    PairTeam(ThreadPair &pair, const int parts);

    int
    n_parts() const override;
    bool
    computes(const int d) const override;
    void
    run(const std::function<void(int)> &f) override;
    void
    share(double *data, const std::size_t m) override;
    void
    share_rows(double                 *data,
               const std::vector<int> &first,
               const int               width) override;
    bool
    same_everywhere(const Eigen::VectorXd &v) override;

  private:
    ThreadPair &pair;
    int         parts;
  };

  /// One subdomain per rank of an MPI communicator; shares by allgather.
  class RankTeam : public PartTeam
  {
  public:
    explicit RankTeam(const MPI_Comm comm);

    int
    n_parts() const override;
    bool
    computes(const int d) const override;
    void
    run(const std::function<void(int)> &f) override;
    void
    share(double *data, const std::size_t m) override;
    void
    share_rows(double                 *data,
               const std::vector<int> &first,
               const int               width) override;
    bool
    same_everywhere(const Eigen::VectorXd &v) override;

  private:
    MPI_Comm         comm;
    int              rank = 0, size = 1;
    std::vector<int> counts, offsets;
  };
} // namespace rockdda::dda::internal

#endif
