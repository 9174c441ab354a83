# Run at build time (cmake -P): writes VERSION_FILE, a source file with the
# project's version and the git commit of SOURCE_DIR ("unknown" outside
# git), only when they changed, so that a new commit relinks softsand
# without recompiling the rest.
# Variables: SOURCE_DIR, VERSION, VERSION_FILE.
set(_commit "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE _hash OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE _result ERROR_QUIET)
  if(_result EQUAL 0 AND NOT _hash STREQUAL "")
    set(_commit "${_hash}")
    # Tracked files changed since the commit: the build is not the commit.
    execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} status --porcelain
                            --untracked-files=no
                    OUTPUT_VARIABLE _status OUTPUT_STRIP_TRAILING_WHITESPACE
                    RESULT_VARIABLE _result ERROR_QUIET)
    if(_result EQUAL 0 AND NOT _status STREQUAL "")
      set(_commit "${_commit}-modified")
    endif()
  endif()
endif()
set(_text "// Written by cmake/softsand_version.cmake at build time.
#include <softsand/base/version.h>

namespace softsand
{
  namespace base
  {
    std::string
    version()
    {
      return \"${VERSION}\";
    }

    std::string
    git_commit()
    {
      return \"${_commit}\";
    }
  } // namespace base
} // namespace softsand
")
if(EXISTS "${VERSION_FILE}")
  file(READ "${VERSION_FILE}" _old)
else()
  set(_old "")
endif()
if(NOT _old STREQUAL _text)
  file(WRITE "${VERSION_FILE}" "${_text}")
endif()
