#include "atpPropertiesPanel.h"

#include "vtkATPMapper.h"

#include "vtkActor.h"
#include "vtkLightKit.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

namespace atp
{
namespace
{

QDoubleSpinBox* MakeSpinBox(const QString& name, double low, double high, double step, double value,
  int decimals = 2)
{
  auto* box = new QDoubleSpinBox;
  box->setObjectName(name);
  box->setRange(low, high);
  box->setSingleStep(step);
  box->setDecimals(decimals);
  box->setValue(value);
  return box;
}

QCheckBox* MakeCheckBox(const QString& name, const QString& text, bool checked)
{
  auto* box = new QCheckBox(text);
  box->setObjectName(name);
  box->setChecked(checked);
  return box;
}

}

PropertiesPanel::PropertiesPanel(
  vtkATPMapper* mapper, vtkActor* actor, vtkRenderer* renderer, QWidget* parent)
  : QWidget(parent)
  , Mapper(mapper)
  , Actor(actor)
  , Renderer(renderer)
{
  vtkProperty* property = actor->GetProperty();

  auto* rendering = new QGroupBox(tr("View-dependent rendering"));
  auto* renderingForm = new QFormLayout(rendering);
  Tolerance = MakeSpinBox("tolerancePixels", 0.1, 1000, 0.5, mapper->GetTolerancePixels());
  Tolerance->setSuffix(tr(" px"));
  Tolerance->setToolTip(tr("Largest screen-space error of the drawn cut"));
  renderingForm->addRow(tr("Screen tolerance"), Tolerance);
  CacheBudget = new QSpinBox;
  CacheBudget->setObjectName("cacheBudget");
  CacheBudget->setRange(1, 1 << 20);
  CacheBudget->setSuffix(tr(" MiB"));
  CacheBudget->setValue(int(mapper->GetCacheBudget() >> 20));
  CacheBudget->setToolTip(tr("GPU memory for patches; a smaller budget settles coarser"));
  renderingForm->addRow(tr("GPU cache budget"), CacheBudget);
  Prefetch = MakeCheckBox("prefetching", tr("Prefetching"), mapper->GetPrefetching());
  Backface = MakeCheckBox("backfaceCulling", tr("Backface culling"), mapper->GetBackfaceCulling());
  PatchColors = MakeCheckBox("patchColoring", tr("Patch coloring"), mapper->GetPatchColoring());
  for (QCheckBox* box : { Prefetch, Backface, PatchColors })
  {
    renderingForm->addRow(box);
  }

  auto* display = new QGroupBox(tr("Lighting and material"));
  auto* displayForm = new QFormLayout(display);
  Representation = new QComboBox;
  Representation->setObjectName("representation");
  Representation->addItems({ tr("Points"), tr("Wireframe"), tr("Surface") }); // VTK_POINTS...
  Representation->setCurrentIndex(property->GetRepresentation());
  displayForm->addRow(tr("Representation"), Representation);
  Color = new QPushButton;
  Color->setObjectName("color");
  ShowColor();
  displayForm->addRow(tr("Color"), Color);
  Ambient = MakeSpinBox("ambient", 0, 1, 0.05, property->GetAmbient());
  Diffuse = MakeSpinBox("diffuse", 0, 1, 0.05, property->GetDiffuse());
  Specular = MakeSpinBox("specular", 0, 1, 0.05, property->GetSpecular());
  SpecularPower = MakeSpinBox("specularPower", 1, 128, 1, property->GetSpecularPower(), 0);
  displayForm->addRow(tr("Ambient"), Ambient);
  displayForm->addRow(tr("Diffuse"), Diffuse);
  displayForm->addRow(tr("Specular"), Specular);
  displayForm->addRow(tr("Specular power"), SpecularPower);
  LightKitBox = MakeCheckBox("lightKit", tr("Light kit (instead of the headlight)"), false);
  displayForm->addRow(LightKitBox);

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(rendering);
  layout->addWidget(display);
  layout->addStretch();

  const auto changed = [this] { emit Changed(); };
  connect(Tolerance, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [=](double px) {
    Mapper->SetTolerancePixels(px);
    changed();
  });
  connect(CacheBudget, qOverload<int>(&QSpinBox::valueChanged), this, [=](int mib) {
    Mapper->SetCacheBudget(vtkTypeInt64(mib) << 20);
    changed();
  });
  connect(Prefetch, &QCheckBox::toggled, this, [=](bool on) {
    Mapper->SetPrefetching(on);
    changed();
  });
  connect(Backface, &QCheckBox::toggled, this, [=](bool on) {
    Mapper->SetBackfaceCulling(on);
    changed();
  });
  connect(PatchColors, &QCheckBox::toggled, this, [=](bool on) {
    Mapper->SetPatchColoring(on);
    changed();
  });
  connect(Representation, qOverload<int>(&QComboBox::currentIndexChanged), this, [=](int index) {
    Actor->GetProperty()->SetRepresentation(index);
    changed();
  });
  connect(Color, &QPushButton::clicked, this, &PropertiesPanel::ChooseColor);
  const std::pair<QDoubleSpinBox*, void (vtkProperty::*)(double)> material[] = {
    { Ambient, &vtkProperty::SetAmbient }, { Diffuse, &vtkProperty::SetDiffuse },
    { Specular, &vtkProperty::SetSpecular }, { SpecularPower, &vtkProperty::SetSpecularPower }
  };
  for (const auto& [box, set] : material)
  {
    connect(box, qOverload<double>(&QDoubleSpinBox::valueChanged), this, [=, set = set](double v) {
      (Actor->GetProperty()->*set)(v);
      changed();
    });
  }
  connect(LightKitBox, &QCheckBox::toggled, this, [=](bool on) {
    UseLightKit(on);
    changed();
  });
}

PropertiesPanel::~PropertiesPanel() = default;

void PropertiesPanel::ChooseColor()
{
  const double* rgb = Actor->GetProperty()->GetColor();
  const QColor chosen =
    QColorDialog::getColor(QColor::fromRgbF(rgb[0], rgb[1], rgb[2]), this, tr("Surface color"));
  if (chosen.isValid())
  {
    Actor->GetProperty()->SetColor(chosen.redF(), chosen.greenF(), chosen.blueF());
    ShowColor();
    emit Changed();
  }
}

void PropertiesPanel::ShowColor()
{
  const double* rgb = Actor->GetProperty()->GetColor();
  const QColor color = QColor::fromRgbF(rgb[0], rgb[1], rgb[2]);
  Color->setText(color.name());
  Color->setStyleSheet(QString("background-color: %1; color: %2")
                         .arg(color.name(), color.lightnessF() > 0.5 ? "black" : "white"));
}

void PropertiesPanel::UseLightKit(bool on)
{
  // Without lights of its own the renderer makes a headlight at the next render.
  Renderer->RemoveAllLights();
  Renderer->SetAutomaticLightCreation(!on);
  if (on)
  {
    Lights->AddLightsToRenderer(Renderer);
  }
}

}
