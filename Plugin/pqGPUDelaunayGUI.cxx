#include "pqGPUDelaunayGUI.h"

#include "pqApplicationCore.h"
#include "pqObjectBuilder.h"
#include "pqCoreUtilities.h"
#include "pqDataRepresentation.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqProgressManager.h"
#include "pqProgressWidget.h"
#include "pqPropertiesPanel.h"
#include "pqServerManagerModel.h"
#include "pqView.h"
#include "vtkAlgorithm.h"
#include "vtkInformation.h"
#include "vtkWeakPointer.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPVDataInformation.h"
#include "vtkSMParaViewPipelineControllerWithRendering.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMSettings.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMViewLayoutProxy.h"
#include "vtkSMViewProxy.h"

#include <QApplication>
#include <QEventLoop>
#include <QEvent>
#include <QMouseEvent>
#include <QTimer>
#include <QToolButton>

#include <cstring>
#include <memory>
#include <utility>
#include <vector>

namespace
{
bool IsMeshingFilter(vtkObject* object)
{
  return object &&
    (object->IsA("vtkGPUConstrainedDelaunay2D") || object->IsA("vtkGPUQualityTetMesh") ||
      object->IsA("vtkGPURestrictedDelaunay3D"));
}

// How a filter's histogram chart is titled: its port, the chart and axis titles, and the
// legend label of each count column.
struct HistogramChart
{
  const char* Proxy;
  int Port;
  const char* Title;
  const char* LeftAxis;
  std::vector<std::pair<const char*, const char*>> Series;
};

const HistogramChart* FindHistogramChart(const char* proxy, int port)
{
  static const HistogramChart charts[] = {
    { "GPUConstrainedDelaunay2D", 1, "Minimum angle per triangle", "triangles",
      { { "bin_values", "triangles" } } },
    { "GPUQualityTetMesh", 1, "Dihedral angles", "dihedral angles",
      { { "DihedralAngleCount", "dihedral angles" } } },
    { "GPURestrictedDelaunay3D", 2, "Angle histograms", "count",
      { { "DihedralAngleCount", "dihedral angles" },
        { "FacetAngleCount", "smallest angle per surface triangle" } } },
  };
  for (const HistogramChart& chart : charts)
  {
    if (strcmp(chart.Proxy, proxy) == 0 && chart.Port == port)
    {
      return &chart;
    }
  }
  return nullptr;
}

// The oldest bar chart view made before `created` that shows one of the meshing filters'
// histograms, if any.
pqView* ExistingHistogramView(pqView* created)
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  pqView* oldest = nullptr;
  for (pqView* view : model->findItems<pqView*>())
  {
    const vtkTypeUInt32 id = view->getProxy()->GetGlobalID();
    if (view->getViewType() != "XYBarChartView" || id >= created->getProxy()->GetGlobalID() ||
      (oldest && id >= oldest->getProxy()->GetGlobalID()))
    {
      continue;
    }
    for (pqRepresentation* r : view->getRepresentations())
    {
      auto* data = qobject_cast<pqDataRepresentation*>(r);
      pqOutputPort* port = data ? data->getOutputPortFromInput() : nullptr;
      if (port && FindHistogramChart(port->getSource()->getProxy()->GetXMLName(), port->getPortNumber()))
      {
        oldest = view;
        break;
      }
    }
  }
  return oldest;
}

// Each new filter's histogram would open one more bar chart view (the proxy's view hint):
// show it in the chart that is already there instead, beside the earlier ones (their eye
// icons hide them), and close the new view.
bool MoveToExistingChart(pqDataRepresentation* histogram, pqOutputPort* port, pqView* created)
{
  pqView* existing = ExistingHistogramView(created);
  if (!existing || created->getNumberOfRepresentations() != 1)
  {
    return false;
  }
  histogram->setVisible(false);
  if (vtkSMViewLayoutProxy* layout = vtkSMViewLayoutProxy::FindLayout(created->getViewProxy()))
  {
    const int cell = layout->RemoveView(created->getViewProxy());
    if (cell >= 0)
    {
      layout->Collapse(cell);
    }
  }
  pqApplicationCore::instance()->getObjectBuilder()->destroy(created); // and the histogram
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  controller->Show(port->getSource()->getSourceProxy(), port->getPortNumber(), existing->getViewProxy());
  existing->render();
  return true;
}

// A restricted Delaunay run without tetrahedra (an open surface, or Mesh Volume off) has its
// mesh in the surface port, which the proxy does not show by default (with tetrahedra it
// would flicker through their boundary faces): show it there, with its edges, instead.
void ShowSurfaceWithoutTetrahedra(pqDataRepresentation* tets, pqOutputPort* port, pqView* view)
{
  pqPipelineSource* source = port->getSource();
  if (port->getDataInformation()->GetNumberOfCells() > 0 || source->getNumberOfOutputPorts() < 2 ||
    source->getOutputPort(1)->getDataInformation()->GetNumberOfCells() == 0)
  {
    return;
  }
  vtkNew<vtkSMParaViewPipelineControllerWithRendering> controller;
  vtkSMProxy* surface = controller->Show(source->getSourceProxy(), 1, view->getViewProxy());
  if (surface)
  {
    vtkSMPropertyHelper(surface, "Representation").Set("Surface With Edges");
    surface->UpdateVTKObjects();
  }
  tets->setVisible(false);
  view->render();
}

// Viridis over [0, top] as a ParaView RGBPoints list (x r g b ...).
QString Viridis(double top)
{
  const double c[5][3] = { { 0.267, 0.005, 0.329 }, { 0.231, 0.322, 0.545 },
    { 0.128, 0.567, 0.551 }, { 0.369, 0.789, 0.383 }, { 0.993, 0.906, 0.144 } };
  QStringList values;
  for (int i = 0; i < 5; ++i)
  {
    values << QString::number(top * i / 4) << QString::number(c[i][0])
           << QString::number(c[i][1]) << QString::number(c[i][2]);
  }
  return values.join(", ");
}
}

//-----------------------------------------------------------------------------
pqGPUDelaunayGUI::pqGPUDelaunayGUI(QObject* parent)
  : Superclass(parent)
{
}

//-----------------------------------------------------------------------------
void pqGPUDelaunayGUI::startup()
{
  // After pqProgressManager's filter, so that this one sees events first (see eventFilter).
  QApplication::instance()->installEventFilter(this);
  pqApplicationCore* core = pqApplicationCore::instance();
  pqServerManagerModel* model = core->getServerManagerModel();
  QObject::connect(model, &pqServerManagerModel::sourceAdded, this,
    &pqGPUDelaunayGUI::onSourceAdded);
  QObject::connect(model, &pqServerManagerModel::representationAdded, this,
    &pqGPUDelaunayGUI::onRepresentationAdded);
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->onSourceAdded(source);
  }
  pqProgressManager* progress = core->getProgressManager();
  QObject::connect(progress, &pqProgressManager::progress, this,
    [this](const QString& text, int) { this->onProgress(text); });
  QObject::connect(progress, &pqProgressManager::abort, this, &pqGPUDelaunayGUI::onAbort);

  // Fixed colour ranges for the quality arrays, at a priority below the user's settings
  // (and not written to the user's settings file).
  // RGB interpolation between the five points: in ParaView's default (diverging) colour
  // space the colours between them pass through white and pink.
  const QString lut = "\"%1\": { \"PVLookupTable\": { \"RGBPoints\": [%2], "
                      "\"ColorSpace\": \"RGB\", \"AutomaticRescaleRangeMode\": -1 } }";
  const QString json = "{ \"array_lookup_tables\": { " + lut.arg("MinAngle", Viridis(60.0)) +
    ", " + lut.arg("MinDihedralAngle", Viridis(70.5)) + " } }";
  vtkSMSettings::GetInstance()->AddCollectionFromString(json.toStdString(), 0.0);
}

//-----------------------------------------------------------------------------
void pqGPUDelaunayGUI::onSourceAdded(pqPipelineSource* source)
{
  this->Watch(source);
}

//-----------------------------------------------------------------------------
vtkAlgorithm* pqGPUDelaunayGUI::Watch(pqPipelineSource* source)
{
  vtkObject* object = vtkObject::SafeDownCast(source->getProxy()->GetClientSideObject());
  if (!IsMeshingFilter(object))
  {
    return nullptr; // not ours, not a builtin session, or its filter not created yet
  }
  if (!this->Watched.contains(object))
  {
    this->Watched.insert(object);
    pqCoreUtilities::connect(
      object, vtkCommand::StartEvent, this, SLOT(onFilterStart(vtkObject*)));
    pqCoreUtilities::connect(object, vtkCommand::EndEvent, this, SLOT(onFilterEnd(vtkObject*)));
  }
  return vtkAlgorithm::SafeDownCast(object);
}

//-----------------------------------------------------------------------------
void pqGPUDelaunayGUI::onFilterStart(vtkObject* caller)
{
  this->Running = vtkAlgorithm::SafeDownCast(caller);
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  this->RunningProxy.clear();
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    if (source->getProxy()->GetClientSideObject() == caller)
    {
      this->RunningProxy = source;
    }
  }
  pqApplicationCore::instance()->getProgressManager()->setEnableAbort(true);
}

//-----------------------------------------------------------------------------
void pqGPUDelaunayGUI::onFilterEnd(vtkObject* caller)
{
  if (caller != this->Running)
  {
    return;
  }
  pqApplicationCore::instance()->getProgressManager()->setEnableAbort(false);
  vtkAlgorithm* algorithm = this->Running;
  this->Running = nullptr;
  if (!algorithm->GetAbortExecute())
  {
    return;
  }
  // VTK marks an aborted output ABORTED and executes it again at the next update, and
  // ParaView 5.11 updates after every render: the run would start over (or, with the
  // abort flag still set, abort again on every render, endlessly). The aborted run leaves
  // an empty output that stays until the user applies again: the Apply button is lit,
  // and applying runs the filter again even without a changed property.
  for (int port = 0; port < algorithm->GetNumberOfOutputPorts(); ++port)
  {
    algorithm->GetOutputInformation(port)->Remove(vtkAlgorithm::ABORTED());
  }
  algorithm->SetAbortOutput(false);
  algorithm->SetAbortExecute(0);
  QPointer<pqProxy> proxy = this->RunningProxy;
  if (!proxy)
  {
    return;
  }
  const QString name = proxy->getSMName();
  vtkOutputWindow::GetInstance()->DisplayText(
    qPrintable(name + ": run aborted; its outputs are empty. Apply to run it again.\n"));
  // A first Apply runs the filter inside pqApplyBehavior's showData and marks the proxy
  // UNMODIFIED after it; showData may process events meanwhile (it does when it opens the
  // histogram's view), so a queued call would run too early. Wait for that mark instead.
  // Later Applies and renders run the filter after their mark: mark it modified now.
  auto connections = std::make_shared<std::vector<QMetaObject::Connection>>();
  if (proxy->modifiedState() == pqProxy::UNINITIALIZED)
  {
    auto first = std::make_shared<QMetaObject::Connection>();
    *first = QObject::connect(proxy, &pqProxy::modifiedStateChanged, this,
      [proxy, first](pqServerManagerModelItem*)
      {
        if (proxy && proxy->modifiedState() == pqProxy::UNMODIFIED)
        {
          QObject::disconnect(*first);
          proxy->setModifiedState(pqProxy::MODIFIED);
        }
      });
    connections->push_back(*first);
  }
  else
  {
    proxy->setModifiedState(pqProxy::MODIFIED);
  }
  // Until it is applied again: Reset keeps it modified (its outputs are still empty), and
  // Apply runs it even without a changed property (the views update dirty proxies only;
  // the panel's applied(proxy) comes before that update).
  vtkWeakPointer<vtkAlgorithm> weak = algorithm;
  QWidget* main = pqCoreUtilities::mainWidget();
  for (pqPropertiesPanel* panel :
    main ? main->findChildren<pqPropertiesPanel*>() : QList<pqPropertiesPanel*>())
  {
    connections->push_back(QObject::connect(panel, &pqPropertiesPanel::resetDone, this,
      [proxy]()
      {
        if (proxy && proxy->modifiedState() == pqProxy::UNMODIFIED)
        {
          proxy->setModifiedState(pqProxy::MODIFIED);
        }
      }));
    connections->push_back(QObject::connect(panel,
      QOverload<pqProxy*>::of(&pqPropertiesPanel::applied), this,
      [proxy, weak, connections](pqProxy* applied)
      {
        if (!proxy || applied != proxy)
        {
          return;
        }
        if (weak)
        {
          weak->Modified();
        }
        proxy->getProxy()->MarkDirty(proxy->getProxy());
        for (const QMetaObject::Connection& connection : *connections)
        {
          QObject::disconnect(connection);
        }
      }));
  }
}

//-----------------------------------------------------------------------------
void pqGPUDelaunayGUI::onProgress(const QString& text)
{
  if (!this->Running)
  {
    // A filter made in the GUI has no VTK object before its first Apply, so its start
    // was not seen: recognise it by the progress text it reports.
    pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
    for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
    {
      vtkAlgorithm* algorithm = this->Watch(source);
      if (algorithm && algorithm->GetProgressText() && text == algorithm->GetProgressText())
      {
        this->onFilterStart(algorithm);
      }
    }
  }
  if (!this->Running || this->InProcessEvents)
  {
    return;
  }
  // Paint the status bar and deliver a click on its abort button. The progress manager
  // filters out key presses and clicks elsewhere while progress is shown. Timers wait: a
  // run from `paraview --script` at startup fired the welcome dialog's timer here, and the
  // dialog waited for ever for a click that the progress manager filtered out (honoured by
  // Qt's event dispatcher on Linux).
  this->InProcessEvents = true;
  QApplication::processEvents(QEventLoop::AllEvents | QEventLoop::X11ExcludeTimers);
  this->InProcessEvents = false;
}

//-----------------------------------------------------------------------------
void pqGPUDelaunayGUI::onAbort()
{
  if (this->Running)
  {
    this->Running->SetAbortExecuteAndUpdateTime();
  }
}

//-----------------------------------------------------------------------------
void pqGPUDelaunayGUI::onRepresentationAdded(pqRepresentation* representation)
{
  // The representation's input is set after it is added: look once the event is done.
  QPointer<pqRepresentation> repr = representation;
  QTimer::singleShot(0, this,
    [repr]()
    {
      auto* data = qobject_cast<pqDataRepresentation*>(repr.data());
      pqView* view = data ? data->getView() : nullptr;
      pqOutputPort* port = data ? data->getOutputPortFromInput() : nullptr;
      if (!view || !port)
      {
        return;
      }
      const char* name = port->getSource()->getProxy()->GetXMLName();
      if (strcmp(name, "GPURestrictedDelaunay3D") == 0 && port->getPortNumber() == 0 &&
        view->getViewType() == "RenderView")
      {
        ShowSurfaceWithoutTetrahedra(data, port, view);
        return;
      }
      const HistogramChart* histogram = FindHistogramChart(name, port->getPortNumber());
      if (!histogram || view->getViewType() != "XYBarChartView" || MoveToExistingChart(data, port, view))
      {
        return; // a moved histogram is styled when its new representation is added
      }
      // The legend names the counted things instead of the column names.
      vtkSMPropertyHelper label(data->getProxy(), "SeriesLabel");
      for (const auto& series : histogram->Series)
      {
        label.SetStatus(series.first, series.second);
      }
      if (histogram->Series.size() > 1)
      {
        // Two series of 180 bars each are too thin to read: the restricted mesher's chart
        // shows the dihedral angles, or the facet angles when there are no tetrahedra.
        const bool tets =
          port->getSource()->getOutputPort(0)->getDataInformation()->GetNumberOfCells() > 0;
        vtkSMPropertyHelper(data->getProxy(), "SeriesVisibility")
          .SetStatus(histogram->Series[tets ? 1 : 0].first, 0);
      }
      // Several runs in one chart (MoveToExistingChart): each named in the legend by its
      // filter, the newest in a colour of its own.
      std::vector<pqDataRepresentation*> runs;
      for (pqRepresentation* r : view->getRepresentations())
      {
        auto* other = qobject_cast<pqDataRepresentation*>(r);
        pqOutputPort* at = other ? other->getOutputPortFromInput() : nullptr;
        if (at && FindHistogramChart(at->getSource()->getProxy()->GetXMLName(), at->getPortNumber()))
        {
          runs.push_back(other);
        }
      }
      if (runs.size() > 1)
      {
        for (pqDataRepresentation* run : runs)
        {
          const QString prefix = run->getOutputPortFromInput()->getSource()->getSMName() + ": ";
          vtkSMPropertyHelper(run->getProxy(), "SeriesLabelPrefix").Set(prefix.toUtf8().constData());
          run->getProxy()->UpdateVTKObjects();
        }
        static double palette[4][3] = { { 0.89, 0.10, 0.11 }, { 0.22, 0.49, 0.72 },
          { 0.30, 0.69, 0.29 }, { 0.60, 0.31, 0.64 } };
        for (const auto& series : histogram->Series)
        {
          vtkSMPropertyHelper(data->getProxy(), "SeriesColor")
            .SetStatus(series.first, palette[(runs.size() - 1) % 4], 3);
        }
      }
      data->getProxy()->UpdateVTKObjects();
      vtkSMProxy* chart = view->getProxy();
      vtkSMPropertyHelper(chart, "ChartTitle").Set(histogram->Title);
      vtkSMPropertyHelper(chart, "BottomAxisTitle").Set("degrees");
      vtkSMPropertyHelper(chart, "LeftAxisTitle").Set(histogram->LeftAxis);
      chart->UpdateVTKObjects();
      view->render();
    });
}

//-----------------------------------------------------------------------------
bool pqGPUDelaunayGUI::eventFilter(QObject* object, QEvent* event)
{
  // While progress is shown, pqProgressManager swallows mouse presses on every object not
  // marked non-blockable. With Qt 5 a press reaches the top-level window (QWidgetWindow)
  // before the widget under the cursor, and that window is not non-blockable, so the
  // abort button never gets the press. A press over the enabled abort button while one
  // of our filters runs is therefore taken here and turned into the abort.
  if (!this->Running || event->type() != QEvent::MouseButtonPress)
  {
    return this->Superclass::eventFilter(object, event);
  }
  QWidget* main = pqCoreUtilities::mainWidget();
  pqProgressWidget* progress = main ? main->findChild<pqProgressWidget*>() : nullptr;
  QToolButton* abort = progress ? progress->abortButton() : nullptr;
  const QPoint at = static_cast<QMouseEvent*>(event)->globalPos();
  if (abort && abort->isEnabled() && abort->isVisible() &&
    abort->rect().contains(abort->mapFromGlobal(at)))
  {
    pqApplicationCore::instance()->getProgressManager()->triggerAbort();
    return true;
  }
  return this->Superclass::eventFilter(object, event);
}
