// VTK XML PolyData (.vtp) input, read whole by vtkXMLPolyDataReader (meant for small inputs);
// its triangles then go through OpenPolyDataTriangleSource like any in-memory vtkPolyData.
#ifndef atpVtpReader_h
#define atpVtpReader_h

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

namespace atp
{

/// Throws InputError naming the file, with VTK's own message when VTK cannot read it.
vtkSmartPointer<vtkPolyData> ReadVtpFile(const std::string& path);

} // namespace atp

#endif
