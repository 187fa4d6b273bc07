// atp extract: one level of detail of a model written out as an ordinary mesh.
#ifndef atpExtractCommand_h
#define atpExtractCommand_h

#include <string>
#include <vector>

namespace atp
{

/// Returns the process exit code; arguments follow the command name.
int ExtractCommand(const std::vector<std::string>& arguments);

}

#endif
