#include "vtkATPExtractCut.h"

#include "atpCameraView.h"
#include "atpCut.h"
#include "atpCutIndex.h"
#include "atpModelFile.h"
#include "atpPatchPolyData.h"
#include "vtkATPModel.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

vtkStandardNewMacro(vtkATPExtractCut);
vtkCxxSetObjectMacro(vtkATPExtractCut, Camera, vtkCamera);

void vtkATPExtractCut::SetViewportSize(int width, int height)
{
  if (width < 1 || height < 1)
  {
    vtkErrorMacro("ViewportSize " << width << " x " << height << " refused: a viewport has at least one pixel each way");
    return;
  }
  if (width != this->ViewportSize[0] || height != this->ViewportSize[1])
  {
    this->ViewportSize[0] = width;
    this->ViewportSize[1] = height;
    this->Modified();
  }
}

void vtkATPExtractCut::SetTolerancePixels(double tolerance)
{
  atp::SetTolerancePixels(this, this->TolerancePixels, tolerance);
}

vtkATPExtractCut::vtkATPExtractCut() = default;

vtkATPExtractCut::~vtkATPExtractCut()
{
  this->SetCamera(nullptr);
}

vtkMTimeType vtkATPExtractCut::GetMTime()
{
  const vtkMTimeType own = this->Superclass::GetMTime();
  return this->Camera ? std::max(own, this->Camera->GetMTime()) : own;
}

int vtkATPExtractCut::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkATPModel");
  return 1;
}

int vtkATPExtractCut::RequestData(
  vtkInformation*, vtkInformationVector** in, vtkInformationVector* out)
{
  vtkPolyData* output = vtkPolyData::GetData(out);
  this->PatchCount = 0;
  vtkATPModel* input = vtkATPModel::GetData(in[0]);
  const atp::ModelFile* model = input ? input->GetModelFile() : nullptr;
  if (!model)
  {
    output->Initialize(); // not the last model's cut
    vtkErrorMacro(<< "the input holds no model");
    return 0;
  }
  try
  {
    std::vector<std::uint32_t> nodes;
    if (this->Level >= 0 || !this->Camera)
    {
      nodes = atp::SelectLevel(*model, this->Level >= 0 ? this->Level : int(model->Header().Depth));
    }
    else
    {
      if (const std::string problem = atp::CameraProblem(this->Camera); !problem.empty())
      {
        throw std::invalid_argument("Camera refused: " + problem);
      }
      atp::ViewPoint view = atp::ViewFromCamera(this->Camera, this->ViewportSize[0],
        this->ViewportSize[1], nullptr, this->TolerancePixels, this->BackfaceCulling);
      if (!this->FrustumCulling)
      {
        view.PlaneCount = 0;
      }
      if (this->IndexedModel != input->GetSharedModelFile())
      {
        this->Index = std::make_shared<const atp::CutIndex>(*model);
        this->IndexedModel = input->GetSharedModelFile();
      }
      atp::CutSelector selector(*model, this->Index);
      atp::CutResult cut;
      selector.Select(view, model->Header().ErrorScale, atp::ResidentFunction(), cut);
      nodes = std::move(cut.Drawn);
    }
    std::vector<std::uint32_t> trianglePatch;
    const atp::PatchMesh mesh =
      atp::ExtractCut(*model, nodes, this->PatchIds ? &trianglePatch : nullptr);
    output->ShallowCopy(atp::PatchMeshToPolyData(mesh));
    if (this->PatchIds)
    {
      vtkNew<vtkIdTypeArray> ids;
      ids->SetName("PatchId");
      ids->SetNumberOfValues(vtkIdType(trianglePatch.size()));
      for (std::size_t t = 0; t < trianglePatch.size(); ++t)
      {
        ids->SetValue(vtkIdType(t), vtkIdType(nodes[trianglePatch[t]]));
      }
      output->GetCellData()->AddArray(ids);
    }
    this->PatchCount = vtkIdType(nodes.size());
  }
  catch (const std::exception& e)
  {
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

void vtkATPExtractCut::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera << "\n";
  os << indent << "ViewportSize: " << this->ViewportSize[0] << " x " << this->ViewportSize[1] << "\n";
  os << indent << "TolerancePixels: " << this->TolerancePixels << "\n";
  os << indent << "BackfaceCulling: " << this->BackfaceCulling << "\n";
  os << indent << "FrustumCulling: " << this->FrustumCulling << "\n";
  os << indent << "Level: " << this->Level << "\n";
  os << indent << "PatchIds: " << this->PatchIds << "\n";
  os << indent << "PatchCount: " << this->PatchCount << "\n";
}
