/**
 * @file
 * Interrupted runs: SIGINT and SIGTERM only set a flag, which the analyses
 * poll between steps; they then write what they have and stop.
 */
#ifndef ROCKDDA_IO_INTERRUPT_H
#define ROCKDDA_IO_INTERRUPT_H

#include <string>

namespace rockdda::io
{
  /**
   * While an object of this class lives, SIGINT and SIGTERM do not end the
   * process: the handler only stores the signal number in a
   * volatile std::sig_atomic_t (nothing else happens in the handler), and
   * the analyses poll interrupt_signal() between steps. The handlers are
   * one-shot (SA_RESETHAND): a second Ctrl-C ends the process at once. The
   * destructor restores the previous handlers.
   */
  class InterruptGuard
  {
  public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard &) = delete;
    InterruptGuard &
    operator=(const InterruptGuard &)
      = delete;
  };

  /// The signal received while an InterruptGuard lived (0 if none).
  int
  interrupt_signal();

  /**
   * interrupt_signal(), agreed by every MPI rank (the largest over
   * MPI_COMM_WORLD; a collective call when MPI is initialised), so that
   * a distributed run stops after the same step on every rank.
   */
  int
  interrupt_signal_all_ranks();

  /// Forget a received signal (for tests).
  void
  clear_interrupt();

  /// "SIGINT", "SIGTERM" or "signal N".
  std::string
  signal_name(const int signal);
} // namespace rockdda::io

#endif
