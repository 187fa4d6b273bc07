// The viewer's properties panel, as in ParaView's: the mapper's view-dependent settings
// (screen tolerance, GPU cache budget, prefetching, backface culling, patch coloring) and the
// look of the surface (representation, color, material, lights). Every change goes straight
// to the mapper, actor or renderer and asks for a render.
#ifndef atpPropertiesPanel_h
#define atpPropertiesPanel_h

#include "vtkNew.h"

#include <QWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QPushButton;
class QSpinBox;
class vtkActor;
class vtkATPMapper;
class vtkLightKit;
class vtkRenderer;

namespace atp
{

class PropertiesPanel : public QWidget
{
  Q_OBJECT

public:
  PropertiesPanel(vtkATPMapper* mapper, vtkActor* actor, vtkRenderer* renderer,
    QWidget* parent = nullptr);
  ~PropertiesPanel() override;

  QDoubleSpinBox* TolerancePixels() const { return Tolerance; }
  QSpinBox* CacheBudgetMiB() const { return CacheBudget; }
  QCheckBox* Prefetching() const { return Prefetch; }
  QCheckBox* BackfaceCulling() const { return Backface; }
  QCheckBox* PatchColoring() const { return PatchColors; }
  QCheckBox* LightKit() const { return LightKitBox; }

signals:
  /// A property changed: the view should render again.
  void Changed();

private:
  void ChooseColor();
  void ShowColor();
  void UseLightKit(bool on);

  vtkATPMapper* Mapper;
  vtkActor* Actor;
  vtkRenderer* Renderer;
  vtkNew<vtkLightKit> Lights;

  QDoubleSpinBox* Tolerance;
  QSpinBox* CacheBudget;
  QCheckBox* Prefetch;
  QCheckBox* Backface;
  QCheckBox* PatchColors;
  QComboBox* Representation;
  QPushButton* Color;
  QDoubleSpinBox* Ambient;
  QDoubleSpinBox* Diffuse;
  QDoubleSpinBox* Specular;
  QDoubleSpinBox* SpecularPower;
  QCheckBox* LightKitBox;
};

}

#endif
