#include "vtkATPModel.h"

#include "atpModelFile.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkATPModel);

void vtkATPModel::SetModelFile(std::shared_ptr<const atp::ModelFile> model)
{
  if (model != this->Model)
  {
    this->Model = std::move(model);
    this->Modified();
  }
}

void vtkATPModel::GetBounds(double bounds[6])
{
  if (!this->Model)
  {
    vtkMath::UninitializeBounds(bounds);
    return;
  }
  const atp::ModelHeader& h = this->Model->Header();
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = h.BoxMin[a];
    bounds[2 * a + 1] = h.BoxMax[a];
  }
}

void vtkATPModel::Initialize()
{
  this->Superclass::Initialize();
  this->Model.reset();
}

void vtkATPModel::ShallowCopy(vtkDataObject* source)
{
  this->Superclass::ShallowCopy(source);
  if (auto* model = vtkATPModel::SafeDownCast(source))
  {
    this->SetModelFile(model->Model);
  }
}

void vtkATPModel::DeepCopy(vtkDataObject* source)
{
  // The model is immutable: sharing the read-only map is a deep copy in effect.
  this->Superclass::DeepCopy(source);
  if (auto* model = vtkATPModel::SafeDownCast(source))
  {
    this->SetModelFile(model->Model);
  }
}

unsigned long vtkATPModel::GetActualMemorySize()
{
  const std::size_t bytes = this->Model ? sizeof(atp::ModelFile) : 0;
  return this->Superclass::GetActualMemorySize() + static_cast<unsigned long>(bytes / 1024);
}

vtkATPModel* vtkATPModel::GetData(vtkInformation* info)
{
  return info ? vtkATPModel::SafeDownCast(info->Get(DATA_OBJECT())) : nullptr;
}

vtkATPModel* vtkATPModel::GetData(vtkInformationVector* v, int i)
{
  return vtkATPModel::GetData(v->GetInformationObject(i));
}

void vtkATPModel::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  if (!this->Model)
  {
    os << indent << "Model: (none)\n";
    return;
  }
  const atp::ModelHeader& h = this->Model->Header();
  os << indent << "Model: " << this->Model->Path() << "\n";
  os << indent << "Nodes: " << this->Model->NodeCount() << "\n";
  os << indent << "Levels: " << h.Depth + 1 << "\n";
  os << indent << "InputTriangles: " << h.InputTriangles << "\n";
  os << indent << "ErrorScale: " << h.ErrorScale << "\n";
}
