#ifndef softsand_base_stop_request_h
#define softsand_base_stop_request_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <string>

namespace softsand
{
  namespace base
  {
    /**
     * A stop asked for from outside: SIGINT (Ctrl-C), SIGTERM or SIGUSR1
     * (mpirun passes SIGUSR1 on to every rank; on SIGINT and SIGTERM it
     * kills the ranks) lets a long run finish its step, write a checkpoint
     * and end with exit_code_stopped, so that `simulation control/restart
     * = true` continues it. SIGINT or SIGTERM again, a second or more
     * after the first, ends it at once; within a second it is the same
     * request (Ctrl-C on mpirun reaches each rank from the terminal and
     * again from mpirun).
     */
    void
    install_stop_handlers();

    /// Whether any rank was asked to stop since the last call (collective
    /// over @p comm; a true answer takes the request).
    bool
    stop_requested(const MPI_Comm comm);

    /// A scene that stopped on request says so on @p out ("Stopped on
    /// request after WHERE: checkpoint written in DIRECTORY; ...") and here
    /// (main's exit code).
    void
    report_stop(const dealii::ConditionalOStream &out,
                const std::string                &where,
                const std::string                &directory);

    bool
    stopped_on_request();

    /// The exit code of a run stopped on request (EX_TEMPFAIL: "try again",
    /// i.e. restart from the checkpoint).
    constexpr int exit_code_stopped = 75;
  } // namespace base
} // namespace softsand

#endif
