#include <rockdda/io/interrupt.h>

#include <deal.II/base/mpi.h>

#include <csignal>

namespace rockdda::io
{
  namespace
  {
    volatile std::sig_atomic_t received_signal = 0;

    struct sigaction previous_int, previous_term;

    extern "C" void
    record_signal(int signal)
    {
      received_signal = signal;
    }
  } // namespace



  InterruptGuard::InterruptGuard()
  {
    received_signal         = 0;
    struct sigaction action = {};
    action.sa_handler       = record_signal;
    sigemptyset(&action.sa_mask);
    // One-shot: the default action is restored as the handler runs, so a
    // second signal ends the process. SA_RESTART: blocking calls go on.
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    sigaction(SIGINT, &action, &previous_int);
    sigaction(SIGTERM, &action, &previous_term);
  }



  InterruptGuard::~InterruptGuard()
  {
    sigaction(SIGINT, &previous_int, nullptr);
    sigaction(SIGTERM, &previous_term, nullptr);
  }



  int
  interrupt_signal()
  {
    return received_signal;
  }



  int
  interrupt_signal_all_ranks()
  {
    const int own = received_signal;
    if (!dealii::Utilities::MPI::job_supports_mpi())
      return own;
    return dealii::Utilities::MPI::max(own, MPI_COMM_WORLD);
  }



  void
  clear_interrupt()
  {
    received_signal = 0;
  }



  std::string
  signal_name(const int signal)
  {
    if (signal == SIGINT)
      return "SIGINT";
    if (signal == SIGTERM)
      return "SIGTERM";
    return "signal " + std::to_string(signal);
  }
} // namespace rockdda::io
