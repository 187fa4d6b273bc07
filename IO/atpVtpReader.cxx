#include "atpVtpReader.h"

#include "atpInputFile.h"
#include "atpVtkErrors.h"

#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataReader.h>

#include <string>

namespace atp
{
namespace
{
/// The NumberOfComponents of the first piece's points other than 3 (read from the file's XML
/// structure, before the data), or 3. VTK would report a mismatch from inside vtkPoints, to its
/// output window, where no observer of the reader sees it.
int PointComponents(vtkXMLPolyDataReader* reader)
{
  vtkXMLDataParser* parser = reader->GetXMLParser();
  vtkXMLDataElement* root = parser ? parser->GetRootElement() : nullptr;
  vtkXMLDataElement* polyData = root ? root->FindNestedElementWithName("PolyData") : nullptr;
  for (int i = 0; polyData && i < polyData->GetNumberOfNestedElements(); ++i)
  {
    vtkXMLDataElement* piece = polyData->GetNestedElement(i);
    vtkXMLDataElement* points = std::string(piece->GetName()) == "Piece"
      ? piece->FindNestedElementWithName("Points")
      : nullptr;
    vtkXMLDataElement* array = points ? points->FindNestedElementWithName("DataArray") : nullptr;
    int components = 1; // VTK's default for an array that does not say
    if (array)
    {
      array->GetScalarAttribute("NumberOfComponents", components);
      if (components != 3)
      {
        return components;
      }
    }
  }
  return 3;
}
} // namespace

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
  const int components = errors->FirstError.empty() ? PointComponents(reader) : 3;
  if (components != 3)
  {
    file.Fail("points with " + std::to_string(components) + " components (a point has 3)");
  }
  reader->Update();
  if (!errors->FirstError.empty() || reader->GetErrorCode() != 0)
  {
    file.Fail("not a readable VTK XML PolyData file" +
      (errors->FirstError.empty() ? std::string() : ": " + errors->FirstError));
  }
  return reader->GetOutput();
}

} // namespace atp
