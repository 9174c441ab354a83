#include <softsand/base/stop_request.h>

#include <csignal>

namespace softsand
{
  namespace base
  {
    namespace
    {
      // pending: not yet taken by stop_requested(); received: ever.
      volatile std::sig_atomic_t pending  = 0;
      volatile std::sig_atomic_t received = 0;
      bool                       stopped  = false;

      extern "C" void
      handle_stop_signal(int signal)
      {
        // A second interrupt means "now": the default action ends the run.
        if (received != 0 && signal != SIGUSR1)
          {
            std::signal(signal, SIG_DFL);
            std::raise(signal);
            return;
          }
        received = 1;
        pending  = 1;
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
