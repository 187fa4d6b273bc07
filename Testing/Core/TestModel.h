// What the model-level tests share: one model of the bundled torus, temporary paths, and a
// counter of VTK error events.
#ifndef atpTestModel_h
#define atpTestModel_h

#include "vtkCallbackCommand.h"
#include "vtkNew.h"

#include <string>

namespace atp
{
namespace test
{

/// A path under /tmp unique to this process.
std::string TempPath(const std::string& name);

/// A model of Data/bumpy-torus.ply with small patches (leaf capacity 1000, patch budget 500),
/// so that cuts have many levels to choose from. Built once per process, removed at exit.
const std::string& TorusModel();

/// Counts the VTK error events of the objects it observes.
struct ErrorCounter
{
  vtkNew<vtkCallbackCommand> Command;
  int Errors = 0;
  ErrorCounter();
};

} // namespace test
} // namespace atp

#endif
