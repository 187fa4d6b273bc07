#include "vtkATPReader.h"

#include "atpModelFile.h"
#include "vtkATPModel.h"

#include "vtkErrorCode.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <sys/stat.h>

vtkStandardNewMacro(vtkATPReader);

vtkATPReader::vtkATPReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkATPReader::~vtkATPReader()
{
  this->SetFileName(nullptr);
}

vtkATPModel* vtkATPReader::GetOutput()
{
  return vtkATPModel::SafeDownCast(this->GetOutputDataObject(0));
}

int vtkATPReader::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkATPModel");
  return 1;
}

int vtkATPReader::RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  vtkInformation* info = out->GetInformationObject(0);
  if (!vtkATPModel::GetData(info))
  {
    vtkATPModel* model = vtkATPModel::New();
    info->Set(vtkDataObject::DATA_OBJECT(), model);
    model->FastDelete();
  }
  return 1;
}

int vtkATPReader::RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  this->Opened.reset();
  this->SetErrorCode(vtkErrorCode::NoError);
  // A file that fails to open has no bounds: the last good file's must not stand for them.
  out->GetInformationObject(0)->Remove(vtkStreamingDemandDrivenPipeline::BOUNDS());
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "no file name set");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return 1;
  }
  struct stat status;
  if (stat(this->FileName, &status) != 0)
  {
    vtkErrorMacro(<< this->FileName << ": cannot open the file");
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    return 1;
  }
  try
  {
    this->Opened = std::make_shared<const atp::ModelFile>(atp::ModelFile::Open(this->FileName));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    return 1;
  }
  const atp::ModelHeader& h = this->Opened->Header();
  const double box[6] = { h.BoxMin[0], h.BoxMax[0], h.BoxMin[1], h.BoxMax[1], h.BoxMin[2],
    h.BoxMax[2] };
  out->GetInformationObject(0)->Set(vtkStreamingDemandDrivenPipeline::BOUNDS(), box, 6);
  return 1;
}

int vtkATPReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  vtkATPModel* output = vtkATPModel::GetData(out);
  output->SetModelFile(this->Opened);
  return this->Opened ? 1 : 0;
}

void vtkATPReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
}
