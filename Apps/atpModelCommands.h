// atp info and atp verify: what a model holds, and whether every byte of it is sound.
#ifndef atpModelCommands_h
#define atpModelCommands_h

#include <string>
#include <vector>

namespace atp
{

/// Each returns the process exit code; arguments follow the command name.
int InfoCommand(const std::vector<std::string>& arguments);
int VerifyCommand(const std::vector<std::string>& arguments);

}

#endif
