// Placeholder translation unit: the module builds (and links its dependencies) before vtkATPMapper lands.
namespace atp
{
int RenderingModuleVersion()
{
  return 1;
}
}
