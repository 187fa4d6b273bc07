#include "atpVtpReader.h"

#include "atpInputFile.h"
#include "atpVtkErrors.h"
#include "atpVtkXmlCheck.h"

#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkXMLPolyDataReader.h>

#include <new>

namespace atp
{
vtkSmartPointer<vtkPolyData> ReadVtpFile(const std::string& path)
{
  const InputFile file(path); // missing or unreadable files get our message, not VTK's

  vtkNew<vtkXMLPolyDataReader> reader;
  vtkNew<VtkErrorCollector> errors;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->AddObserver(vtkCommand::WarningEvent, errors);
  reader->SetParserErrorObserver(errors); // malformed XML
  // The executive's own report of the failure, with a dump of its request, would follow.
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  if (errors->FirstError.empty())
  {
    CheckVtkXmlFile(reader, file);
  }
  try
  {
    reader->Update();
  }
  catch (const std::bad_alloc&)
  {
    file.Fail("not enough memory to read it");
  }
  if (!errors->FirstError.empty() || reader->GetErrorCode() != 0)
  {
    file.Fail("not a readable VTK XML PolyData file" +
      (errors->FirstError.empty() ? std::string() : ": " + errors->FirstError));
  }
  return reader->GetOutput();
}

} // namespace atp
