#include "atpPngFile.h"

#include "atpPendingFile.h"
#include "atpFirstVtkError.h"
#include "atpVtkErrorMessage.h"

#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"

namespace atp
{

void WritePng(vtkImageData* image, PendingFile& file)
{
  FirstVtkError errors;
  vtkNew<vtkPNGWriter> writer;
  errors.Watch(writer);
  writer->SetInputData(image);
  writer->SetFileName(file.PartialPath().c_str());
  writer->Write();
  if (writer->GetErrorCode() != vtkErrorCode::NoError)
  {
    throw file.Failure(VtkErrorCodeText(writer->GetErrorCode()));
  }
  if (!errors.Message.empty())
  {
    throw file.Failure(errors.Message);
  }
  vtkNew<vtkPNGReader> reader;
  errors.Watch(reader);
  reader->SetFileName(file.PartialPath().c_str());
  reader->Update();
  int written[3], read[3];
  image->GetDimensions(written);
  reader->GetOutput()->GetDimensions(read);
  if (!errors.Message.empty() || read[0] != written[0] || read[1] != written[1])
  {
    throw file.Failure("the file read back is incomplete");
  }
}

}
