#include "vtkATPBuilder.h"

#include "atpConstruction.h"
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

#include <chrono>
#include <stdexcept>

vtkStandardNewMacro(vtkATPBuilder);

struct vtkATPBuilder::Results
{
  atp::InputStats Input;
  atp::PartitionStats Partition;
  atp::ConstructionStats Construction;
  double PartitionSeconds = 0;
  double ConstructionSeconds = 0;
};

namespace
{
double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}

vtkATPBuilder::vtkATPBuilder()
  : Last(std::make_unique<Results>())
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(0);
}

vtkATPBuilder::~vtkATPBuilder()
{
  this->SetInputFileName(nullptr);
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
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1); // an InputFileName streams instead
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
  if (this->GetNumberOfInputConnections(0) == 0 && !this->InputFileName)
  {
    this->ErrorMessage = "no input: set an InputFileName or connect a vtkPolyData";
    vtkErrorMacro(<< this->ErrorMessage);
    return 0;
  }
  if (!this->FileName || !*this->FileName)
  {
    this->ErrorMessage = "no output: set the FileName of the model to write";
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
    auto phaseStart = std::chrono::steady_clock::now(); // opening reads the input once
    std::unique_ptr<atp::TriangleSource> source;
    if (this->InputFileName)
    {
      source = atp::OpenTriangleSource(this->InputFileName, scratch);
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
    options.Colors = source->HasColors();

    this->ExpectedTriangles = source->ExpectedTriangles();
    const double expected = double(this->ExpectedTriangles);
    // Partitioning streams at several million triangles/s, simplification at about one
    // million: the shares of the progress bar follow.
    constexpr double PartitionShare = 0.15;
    this->SetProgressText("partitioning");
    this->UpdateProgress(0);
    auto partitioner = atp::PartitionStream(*source, options, [&](std::uint64_t done) {
      if (expected > 0)
      {
        this->UpdateProgress(PartitionShare * std::min(1.0, double(done) / expected));
      }
      this->ThrowIfAborted();
    });
    this->Last->Input = source->Stats();
    this->Last->Partition = partitioner->Stats();
    this->Last->PartitionSeconds = SecondsSince(phaseStart);
    phaseStart = std::chrono::steady_clock::now();
    const atp::Box bounds = source->Bounds();
    source.reset(); // its scratch arrays (vertices, sketch) are no longer needed

    atp::ConstructionOptions construction;
    construction.PatchBudget = std::uint32_t(this->PatchBudget);
    construction.Threads = this->NumberOfThreads;
    construction.Runner = this->JobRunner;
    construction.ScratchDirectory = scratch;
    this->SetProgressText("simplifying");
    this->Last->Construction = atp::BuildModel(*partitioner, bounds, this->Last->Input,
      construction, this->FileName, [&](double fraction) {
        this->UpdateProgress(PartitionShare + (1 - PartitionShare) * fraction);
        this->ThrowIfAborted();
      });
    this->Last->ConstructionSeconds = SecondsSince(phaseStart);
    this->UpdateProgress(1);
  }
  catch (const std::exception& e)
  {
    this->ErrorMessage = e.what();
    vtkErrorMacro(<< this->ErrorMessage);
  }
  // Like vtkWriter: the failure is reported once, above, and kept for Build(); a failed
  // request would make the executive print a second, less helpful error.
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

const atp::ConstructionStats& vtkATPBuilder::GetConstructionStats() const
{
  return this->Last->Construction;
}

double vtkATPBuilder::GetPartitionSeconds() const
{
  return this->Last->PartitionSeconds;
}

double vtkATPBuilder::GetConstructionSeconds() const
{
  return this->Last->ConstructionSeconds;
}

void vtkATPBuilder::ThrowIfAborted()
{
  if (this->GetAbortExecute())
  {
    throw std::runtime_error("build cancelled");
  }
}

void vtkATPBuilder::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "InputFileName: " << (this->InputFileName ? this->InputFileName : "(none)")
     << "\n";
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "LeafCapacity: " << this->LeafCapacity << "\n";
  os << indent << "PatchBudget: " << this->PatchBudget << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "JobRunner: " << (this->JobRunner ? "external" : "threads") << "\n";
  os << indent << "BucketMemoryMiB: " << this->BucketMemoryMiB << "\n";
  os << indent << "ScratchDirectory: "
     << (this->ScratchDirectory ? this->ScratchDirectory : "(default)") << "\n";
}
