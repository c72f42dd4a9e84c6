/**
 * @file
 * The interface every analysis type implements, and what a run hands it.
 */
#ifndef ROCKDDA_IO_ANALYSIS_H
#define ROCKDDA_IO_ANALYSIS_H

#include <rockdda/io/output.h>

#include <memory>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace rockdda::io
{
  /**
   * What a running analysis may use: the output folder, the log and the
   * summary of key scalars (summary.csv). The driver writes parameters.prm,
   * summary.csv and log.txt; the analysis writes its own files (at least
   * statistics.csv) through @p output.
   */
  struct RunContext
  {
    const OutputDirectory &output;
    Log                   &log;
    Summary               &summary;
    /**
     * Set by an analysis that stopped early on SIGINT or SIGTERM
     * (interrupt_signal() polled between steps) after writing what it has:
     * statistics.csv so far, the summary of the state reached and, if it
     * supports them, a checkpoint. The driver then writes summary.csv with
     * the row 'completed,0,-' and log.txt, and exits with 128 + the signal.
     */
    bool stopped_early = false;
    /// What the analysis wrote when it stopped early (for the message).
    std::string stopped_note;
  };

  /**
   * One kind of analysis, selected by the top-level key "Analysis type". It
   * declares the parameter sections it owns, reads and checks them (loading
   * every input file) without writing anything, and then runs.
   */
  class Analysis
  {
  public:
    virtual ~Analysis() = default;

    /// The value of "Analysis type" that selects this analysis.
    virtual std::string
    name() const = 0;

    /// One line for --help.
    virtual std::string
    description() const = 0;

    /// Declare the subsections this analysis owns (not the shared ones).
    virtual void
    declare_parameters(dealii::ParameterHandler &prm) const = 0;

    /**
     * Read and validate every value this analysis uses from @p prm and load
     * its input files; throw InputError (naming @p parameter_file and the
     * key) for anything invalid. Writes nothing.
     */
    virtual void
    parse_parameters(dealii::ParameterHandler &prm,
                     const std::string        &parameter_file)
      = 0;

    /// Run the analysis.
    virtual void
    run(RunContext &context)
      = 0;

    /**
     * True if the run continues an earlier one from its checkpoint (key
     * 'Resume'); the driver then keeps the earlier run's files in the output
     * folder instead of deleting them.
     */
    virtual bool
    resumes() const
    {
      return false;
    }

    /**
     * Warnings about the parsed input that do not make it invalid (a
     * penalty too low for the load, a modulus outside the range of rock,
     * ...), each naming the value that would be plausible. Printed by
     * --validate and written to log.txt by a run.
     */
    virtual std::vector<std::string>
    warnings() const
    {
      return {};
    }
  };

  /// Every analysis type the driver knows.
  std::vector<std::unique_ptr<Analysis>>
  all_analyses();

  /**
   * Declare every parameter the driver knows: the top level, the shared
   * sections, and each analysis's own sections.
   */
  void
  declare_all_parameters(
    dealii::ParameterHandler                     &prm,
    const std::vector<std::unique_ptr<Analysis>> &analyses);

  /**
   * The driver: rockdda [--validate] [--print-parameters] [FILE.prm].
   * Returns the process exit code (0 success, 1 bad input, 2 usage, 3 run-time
   * failure, 128 + N after signal N: 130 for SIGINT, 143 for SIGTERM).
   */
  int
  run_driver(int argc, char **argv);

  /**
   * True if this process was started by an MPI launcher (mpirun, mpiexec,
   * srun: their environment variables are set) or ROCKDDA_MPI=1; the driver
   * then initialises MPI. A plain serial run does not (MPI start-up costs
   * ~0.3 s).
   */
  bool
  started_by_mpi_launcher();
} // namespace rockdda::io

#endif
