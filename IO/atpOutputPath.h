// What every command that writes a file checks before its work: the output is written beside
// its final name and renamed into place, so the name must take a new file by rename.
#ifndef atpOutputPath_h
#define atpOutputPath_h

#include "vtkATPIOModule.h"

#include <string>
#include <vector>

namespace atp
{

/// The longest suffix a side file adds to the output's name (".partial-" and a process id and
/// attempt, or mkstemp's six characters).
constexpr std::size_t SideFileSuffixBytes = 32;

/// Why `path` cannot take a new file by rename, or an empty string when it can: it must name a
/// file (not a directory) in a directory that exists, what is there now, if anything, must be a regular file (a device,
/// FIFO or socket would be replaced by the rename, /dev/null too when run as root) and none of
/// `inputs` (a build would replace its own input), and the name must leave room for the side
/// file's suffix within the directory's limit on name length, and the path within the system's.
VTKATPIO_EXPORT std::string OutputPathProblem(
  const std::string& path, const std::vector<std::string>& inputs = {});

} // namespace atp

#endif
