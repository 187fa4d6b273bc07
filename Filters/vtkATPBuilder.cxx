#include "vtkATPBuilder.h"

#include "atpConstruction.h"
#include "atpCpuTime.h"
#include "atpOutputPath.h"
#include "atpStreamPartition.h"
#include "atpTriangleSource.h"
#include "atpPolyDataTriangleSource.h"
#include "atpVolumeTriangleSource.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCommand.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <new>
#include <stdexcept>

vtkStandardNewMacro(vtkATPBuilder);

struct vtkATPBuilder::Results
{
  atp::InputStats Input;
  atp::PartitionStats Partition;
  atp::ConstructionStats Construction;
  atp::SlabContourStats Volume;
  bool FromVolume = false;
  double PartitionSeconds = 0;
  double ConstructionSeconds = 0;
  double PartitionCpuSeconds = 0;
  double ConstructionCpuSeconds = 0;
};

namespace
{
// Partitioning streams at several million triangles/s, simplification at about one million:
// the shares of the progress bar follow. Contouring a volume takes the first part of the
// partitioning's share.
constexpr double PartitionShare = 0.15;
constexpr double ContourShare = 0.1;
/// How messages name a vtkPolyData input.
constexpr const char* PolyDataInputName = "input polydata";

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}

vtkATPBuilder::vtkATPBuilder()
  : IsoValue(std::numeric_limits<double>::quiet_NaN())
  , SlabSlices(atp::DefaultSlabSlices)
  , Last(std::make_unique<Results>())
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

void vtkATPBuilder::SetRawVolumeLayout(const atp::RawVolumeLayout* layout)
{
  this->RawLayout = layout ? std::make_unique<atp::RawVolumeLayout>(*layout) : nullptr;
  this->Modified();
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

std::string vtkATPBuilder::MissingSetting()
{
  if (this->GetNumberOfInputConnections(0) == 0 && !this->InputFileName)
  {
    return "no input: set an InputFileName or connect a vtkPolyData";
  }
  if (!this->FileName || !*this->FileName)
  {
    return "no output: set the FileName of the model to write";
  }
  return std::string();
}

int vtkATPBuilder::Build()
{
  this->ErrorMessage = this->MissingSetting();
  if (!this->ErrorMessage.empty())
  {
    vtkErrorMacro(<< this->ErrorMessage);
    return 0;
  }
  // RequestData clears this; when an algorithm upstream fails, the executive never calls it.
  this->ErrorMessage = "the input pipeline failed (see the errors before this one)";
  this->Modified(); // every call builds, like vtkWriter::Write
  this->Update();
  return this->ErrorMessage.empty() ? 1 : 0;
}

int vtkATPBuilder::RequestData(vtkInformation*, vtkInformationVector** inputs, vtkInformationVector*)
{
  this->ErrorMessage.clear();
  this->WarningMessage.clear();
  this->ExpectedTriangles = 0; // until this build's input is open
  // Figures go to Last only once the build has succeeded: they are the last successful one's.
  Results running;
  const std::string scratch = this->ScratchDirectory ? this->ScratchDirectory : "";
  try
  {
    if (const std::string missing = this->MissingSetting(); !missing.empty())
    {
      throw std::runtime_error(missing); // Update() called without Build()'s checks
    }
    auto phaseStart = std::chrono::steady_clock::now(); // opening reads the input once
    double phaseCpuStart = atp::ProcessCpuSeconds();
    const std::string outputProblem = atp::OutputPathProblem(this->FileName,
      this->InputFileName ? std::vector<std::string>{ this->InputFileName } : std::vector<std::string>{});
    if (!outputProblem.empty())
    {
      throw std::runtime_error(std::string(this->FileName) + ": " + outputProblem);
    }
    std::unique_ptr<atp::TriangleSource> source = this->OpenSource(inputs, running);
    atp::CheckCoordinateRange(source->Bounds(), this->InputFileName ? this->InputFileName : PolyDataInputName);
    atp::PartitionOptions options;
    options.LeafCapacity = std::uint32_t(this->LeafCapacity);
    options.BucketMemoryBytes = std::size_t(this->BucketMemoryMiB) << 20;
    options.ScratchDirectory = scratch;
    options.Colors = source->HasColors();

    this->ExpectedTriangles = source->ExpectedTriangles();
    const double expected = double(this->ExpectedTriangles);
    const double partitionStart = running.FromVolume ? ContourShare : 0;
    this->SetProgressText("partitioning");
    this->UpdateProgress(partitionStart);
    auto partitioner = atp::PartitionStream(*source, options, [&](std::uint64_t done) {
      if (expected > 0)
      {
        this->UpdateProgress(partitionStart +
          (PartitionShare - partitionStart) * std::min(1.0, double(done) / expected));
      }
      this->ThrowIfAborted();
    });
    running.Input = source->Stats();
    running.Partition = partitioner->Stats();
    running.PartitionSeconds = SecondsSince(phaseStart);
    running.PartitionCpuSeconds = atp::ProcessCpuSeconds() - phaseCpuStart;
    phaseStart = std::chrono::steady_clock::now();
    phaseCpuStart = atp::ProcessCpuSeconds();
    const atp::Box bounds = source->Bounds();
    source.reset(); // its scratch arrays (vertices, sketch) are no longer needed

    atp::ConstructionOptions construction;
    construction.PatchBudget = std::uint32_t(this->PatchBudget);
    construction.Order = this->FastCacheOrder ? atp::CacheOrder::Fast : atp::CacheOrder::Best;
    construction.Threads = this->NumberOfThreads;
    construction.Runner = this->JobRunner;
    construction.ScratchDirectory = scratch;
    this->SetProgressText("simplifying");
    running.Construction = atp::BuildModel(*partitioner, bounds, running.Input,
      construction, this->FileName, [&](double fraction) {
        this->UpdateProgress(PartitionShare + (1 - PartitionShare) * fraction);
        this->ThrowIfAborted();
      });
    running.ConstructionSeconds = SecondsSince(phaseStart);
    running.ConstructionCpuSeconds = atp::ProcessCpuSeconds() - phaseCpuStart;
    *this->Last = running;
    this->UpdateProgress(1);
    if (const std::uint64_t atRandom = this->Last->Construction.DiamondsFacingAtRandom)
    {
      // The model is whole and valid, only its shading suffers: a warning, not a failure.
      this->WarningMessage = "the input's triangles are wound either way at random (in " +
        std::to_string(atRandom) + " of " + std::to_string(this->Last->Construction.Diamonds) +
        " diamonds): normals summed over such faces are noise and the model keeps the input's "
        "winding, so it shades speckled; orient the triangles consistently first (in VTK: "
        "vtkPolyDataNormals with ConsistencyOn)";
      vtkWarningMacro(<< this->WarningMessage);
    }
  }
  catch (const std::bad_alloc&)
  {
    this->ErrorMessage = "out of memory (an allocation failed)";
    vtkErrorMacro(<< this->ErrorMessage);
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

double vtkATPBuilder::GetPartitionCpuSeconds() const
{
  return this->Last->PartitionCpuSeconds;
}

double vtkATPBuilder::GetConstructionCpuSeconds() const
{
  return this->Last->ConstructionCpuSeconds;
}

std::unique_ptr<atp::TriangleSource> vtkATPBuilder::OpenSource(
  vtkInformationVector** inputs, Results& running)
{
  const std::string scratch = this->ScratchDirectory ? this->ScratchDirectory : "";
  const bool isoValueSet = !std::isnan(this->IsoValue);
  if (!this->InputFileName)
  {
    if (isoValueSet)
    {
      throw std::invalid_argument("an IsoValue is only for a volume InputFileName");
    }
    vtkPolyData* mesh = vtkPolyData::GetData(inputs[0]);
    return atp::OpenPolyDataTriangleSource(mesh, PolyDataInputName, scratch);
  }
  const std::string path = this->InputFileName;
  if (!this->RawLayout && !atp::IsVolumeFileName(path))
  {
    if (isoValueSet)
    {
      throw std::invalid_argument(path + ": an iso value is only for volumes (.nii, .nii.gz, "
                                         ".vti or raw), this is a mesh");
    }
    return atp::OpenTriangleSource(path, scratch);
  }
  if (!isoValueSet)
  {
    throw std::invalid_argument(path + ": a volume needs an iso value (the surface to build)");
  }
  atp::VolumeOptions options;
  options.IsoValue = this->IsoValue;
  options.SlabSlices = this->SlabSlices;
  options.Raw = this->RawLayout != nullptr;
  if (this->RawLayout)
  {
    options.RawLayout = *this->RawLayout;
  }
  this->SetProgressText("contouring");
  this->UpdateProgress(0);
  auto source = atp::OpenVolumeTriangleSource(
    path, options, scratch, &running.Volume, [this](double fraction) {
      this->UpdateProgress(ContourShare * fraction);
      this->ThrowIfAborted();
    });
  running.FromVolume = true;
  return source;
}

const atp::SlabContourStats* vtkATPBuilder::GetVolumeStats() const
{
  return this->Last->FromVolume ? &this->Last->Volume : nullptr;
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
  os << indent << "IsoValue: " << this->IsoValue << "\n";
  os << indent << "SlabSlices: " << this->SlabSlices << "\n";
  os << indent << "RawVolumeLayout: " << (this->RawLayout ? "set" : "(none)") << "\n";
  os << indent << "LeafCapacity: " << this->LeafCapacity << "\n";
  os << indent << "PatchBudget: " << this->PatchBudget << "\n";
  os << indent << "FastCacheOrder: " << (this->FastCacheOrder ? "on" : "off") << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "JobRunner: " << (this->JobRunner ? "external" : "threads") << "\n";
  os << indent << "BucketMemoryMiB: " << this->BucketMemoryMiB << "\n";
  os << indent << "ScratchDirectory: "
     << (this->ScratchDirectory ? this->ScratchDirectory : "(default)") << "\n";
}
