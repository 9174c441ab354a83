#ifndef softsand_base_version_h
#define softsand_base_version_h

#include <string>

namespace softsand
{
  namespace base
  {
    /// The version of softsand (CMake's project version).
    std::string
    version();

    /// The git commit softsand was built from, taken at build time: a short
    /// hash, with "-modified" when tracked files differed from it, or
    /// "unknown" when the sources were not in git.
    std::string
    git_commit();

    /// "softsand VERSION (commit COMMIT)": the first line of a run's log and
    /// of the parameters.prm it writes.
    inline std::string
    version_line()
    {
      return "softsand " + version() + " (commit " + git_commit() + ")";
    }
  } // namespace base
} // namespace softsand

#endif
