#include <softsand/base/warnings.h>

#include <algorithm>
#include <iostream>

namespace softsand
{
  namespace base
  {
    namespace
    {
      std::vector<std::string> given;
      std::vector<std::string> keys_given;
      std::ostream            *warning_log = nullptr;
    } // namespace


    void
    warn(const std::string &message, const MPI_Comm comm)
    {
      if (std::find(given.begin(), given.end(), message) != given.end())
        return;
      given.push_back(message);
      if (dealii::Utilities::MPI::this_mpi_process(comm) != 0)
        return;
      std::cerr << "softsand: warning: " << message << std::endl;
      if (warning_log != nullptr)
        *warning_log << "softsand: warning: " << message << std::endl;
    }


    void
    warn_once(const std::string &key,
              const std::string &message,
              const MPI_Comm     comm)
    {
      if (std::find(keys_given.begin(), keys_given.end(), key) !=
          keys_given.end())
        return;
      keys_given.push_back(key);
      warn(message, comm);
    }


    void
    set_warning_log(std::ostream *log)
    {
      warning_log = log;
    }


    const std::vector<std::string> &
    warnings_given()
    {
      return given;
    }
  } // namespace base
} // namespace softsand
