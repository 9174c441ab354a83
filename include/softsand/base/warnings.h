#ifndef softsand_base_warnings_h
#define softsand_base_warnings_h

#include <deal.II/base/mpi.h>

#include <ostream>
#include <string>
#include <vector>

namespace softsand
{
  namespace base
  {
    /**
     * Warns that a scene runs outside its model's validity or on doubtful
     * input: "softsand: warning: MESSAGE" on the error stream of rank 0 and
     * in the run's log, once per message and run. The run goes on.
     */
    void
    warn(const std::string &message, const MPI_Comm comm);

    /// As warn(), once per @p key: for messages that carry the values at
    /// the moment they are first met.
    void
    warn_once(const std::string &key,
              const std::string &message,
              const MPI_Comm     comm);

    /// Warnings also go to @p log (nullptr: none), e.g. a run's log.txt.
    void
    set_warning_log(std::ostream *log);

    /// The warnings given so far (for tests).
    const std::vector<std::string> &
    warnings_given();
  } // namespace base
} // namespace softsand

#endif
