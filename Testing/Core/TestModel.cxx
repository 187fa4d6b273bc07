#include "TestModel.h"

#include "vtkATPBuilder.h"

#include <cstdlib>
#include <stdexcept>
#include <unistd.h>

namespace atp
{
namespace test
{

std::string TempPath(const std::string& name)
{
  return "/tmp/atp-test-" + std::to_string(::getpid()) + "-" + name;
}

const std::string& TorusModel()
{
  static const std::string path = [] {
    const std::string model = TempPath("torus.atp");
    vtkNew<vtkATPBuilder> builder;
    builder->SetInputFileName(ATP_DATA_DIR "/bumpy-torus.ply");
    builder->SetFileName(model.c_str());
    builder->SetLeafCapacity(1000);
    builder->SetPatchBudget(500);
    if (!builder->Build())
    {
      throw std::runtime_error("the test model did not build");
    }
    std::atexit([] { ::unlink(TempPath("torus.atp").c_str()); });
    return model;
  }();
  return path;
}

ErrorCounter::ErrorCounter()
{
  Command->SetClientData(this);
  Command->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    ++static_cast<ErrorCounter*>(self)->Errors;
  });
}

} // namespace test
} // namespace atp
