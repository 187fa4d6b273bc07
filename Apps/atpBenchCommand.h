// atp bench: the standard flythrough of a model, timed, with per-frame statistics, a summary,
// the paper's figure 7 as a plot, and the speed-up over the full-resolution mesh.
#ifndef atpBenchCommand_h
#define atpBenchCommand_h

#include <string>
#include <vector>

namespace atp
{

/// Returns the process exit code; arguments follow the command name.
int BenchCommand(const std::vector<std::string>& arguments);

}

#endif
