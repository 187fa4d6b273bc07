#include "vtkATPBuilder.h"

#include "atpStreamPartition.h"
#include "atpTriangleSource.h"
#include "atpPolyDataTriangleSource.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCommand.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <stdexcept>

vtkStandardNewMacro(vtkATPBuilder);

struct vtkATPBuilder::Results
{
  atp::InputStats Input;
  atp::PartitionStats Partition;
};

vtkATPBuilder::vtkATPBuilder()
  : Last(std::make_unique<Results>())
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(0);
}

vtkATPBuilder::~vtkATPBuilder()
{
  this->SetFileName(nullptr);
  this->SetScratchDirectory(nullptr);
}

void vtkATPBuilder::SetInputData(vtkPolyData* mesh)
{
  this->SetInputDataInternal(0, mesh);
}

int vtkATPBuilder::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1); // a FileName streams instead
  return 1;
}

vtkTypeBool vtkATPBuilder::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  // A sink like vtkWriter: the pipeline's data request runs the build.
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inputs, outputs);
  }
  return this->Superclass::ProcessRequest(request, inputs, outputs);
}

int vtkATPBuilder::Build()
{
  if (this->GetNumberOfInputConnections(0) == 0 && !this->FileName)
  {
    this->ErrorMessage = "no input: set a FileName or connect a vtkPolyData";
    vtkErrorMacro(<< this->ErrorMessage);
    return 0;
  }
  this->ErrorMessage.clear();
  this->Modified(); // every call builds, like vtkWriter::Write
  this->Update();
  return this->ErrorMessage.empty() ? 1 : 0;
}

int vtkATPBuilder::RequestData(vtkInformation*, vtkInformationVector** inputs, vtkInformationVector*)
{
  this->ErrorMessage.clear();
  const std::string scratch = this->ScratchDirectory ? this->ScratchDirectory : "";
  try
  {
    std::unique_ptr<atp::TriangleSource> source;
    if (this->FileName)
    {
      source = atp::OpenTriangleSource(this->FileName, scratch);
    }
    else
    {
      vtkPolyData* mesh = vtkPolyData::GetData(inputs[0]);
      source = atp::OpenPolyDataTriangleSource(mesh, "input polydata", scratch);
    }
    atp::PartitionOptions options;
    options.LeafCapacity = std::uint32_t(this->LeafCapacity);
    options.BucketMemoryBytes = std::size_t(this->BucketMemoryMiB) << 20;
    options.ScratchDirectory = scratch;

    this->ExpectedTriangles = source->ExpectedTriangles();
    const double expected = double(this->ExpectedTriangles);
    this->SetProgressText("partitioning");
    this->UpdateProgress(0);
    auto partitioner = atp::PartitionStream(*source, options, [&](std::uint64_t done) {
      if (expected > 0)
      {
        this->UpdateProgress(std::min(1.0, double(done) / expected));
      }
    });
    this->Last->Input = source->Stats();
    this->Last->Partition = partitioner->Stats();
    this->UpdateProgress(1);
  }
  catch (const std::exception& e)
  {
    this->ErrorMessage = e.what();
    vtkErrorMacro(<< this->ErrorMessage);
    return 0;
  }
  return 1;
}

const atp::InputStats& vtkATPBuilder::GetInputStats() const
{
  return this->Last->Input;
}

const atp::PartitionStats& vtkATPBuilder::GetPartitionStats() const
{
  return this->Last->Partition;
}

void vtkATPBuilder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "LeafCapacity: " << this->LeafCapacity << "\n";
  os << indent << "BucketMemoryMiB: " << this->BucketMemoryMiB << "\n";
  os << indent << "ScratchDirectory: "
     << (this->ScratchDirectory ? this->ScratchDirectory : "(default)") << "\n";
}
