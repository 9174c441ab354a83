#include <softsand/base/stop_request.h>

#include <csignal>
#include <ctime>

namespace softsand
{
  namespace base
  {
    namespace
    {
      // pending: not yet taken by stop_requested(); first: when the first
      // request came (steady clock, s; 0: none yet).
      volatile std::sig_atomic_t pending = 0;
      double                     first   = 0;
      bool                       stopped = false;

      double
      now()
      {
        timespec t; // clock_gettime is async-signal-safe
        clock_gettime(CLOCK_MONOTONIC, &t);
        return t.tv_sec + 1e-9 * t.tv_nsec;
      }

      extern "C" void
      handle_stop_signal(int signal)
      {
        // An interrupt a second or more after the first means "now": the
        // default action ends the run. One within a second does not:
        // Ctrl-C on mpirun reaches every rank twice, from the terminal and
        // from mpirun, and mpirun adds SIGTERM.
        const double t = now();
        if (first > 0 && t > first + 1 && signal != SIGUSR1)
          {
            std::signal(signal, SIG_DFL);
            std::raise(signal);
            return;
          }
        if (first == 0)
          first = t;
        pending = 1;
      }
    } // namespace


    void
    install_stop_handlers()
    {
      for (const int s : {SIGINT, SIGTERM, SIGUSR1})
        std::signal(s, handle_stop_signal);
    }


    bool
    stop_requested(const MPI_Comm comm)
    {
      const unsigned int mine = (pending != 0) ? 1 : 0;
      const bool         any  = dealii::Utilities::MPI::max(mine, comm) != 0;
      if (any)
        pending = 0;
      return any;
    }


    void
    report_stop(const dealii::ConditionalOStream &out,
                const std::string                &where,
                const std::string                &directory)
    {
      out << "Stopped on request after " << where
          << ": checkpoint written in " << directory
          << "; set simulation control/restart = true to continue."
          << std::endl;
      stopped = true;
    }


    bool
    stopped_on_request()
    {
      return stopped;
    }
  } // namespace base
} // namespace softsand
