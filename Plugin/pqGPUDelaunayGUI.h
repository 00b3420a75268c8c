/**
 * @class   pqGPUDelaunayGUI
 * @brief   ParaView GUI glue of the plugin (auto-start): progress, abort, default colours
 *
 * ParaView 5.11's GUI does not process Qt events while a filter executes (its progress
 * manager leaves processEvents commented out) and never enables the status bar's abort
 * button for filters. The progress handler does forward our filters' progress (at most
 * every 0.1 s), but nothing is painted or clicked until the run ends. While one of this
 * plugin's meshing filters executes, this component therefore
 *  - processes pending Qt events on each forwarded progress event, so that the status bar
 *    shows the phase and the percentage and the window repaints (the progress manager
 *    still swallows key presses and clicks outside the progress bar and its abort button),
 *  - enables the abort button and, when it is pressed, sets the running filter's abort
 *    flag (vtkAlgorithm::SetAbortExecuteAndUpdateTime), which the engine checks between
 *    its phases; the aborted filter's output is empty, its Apply button lit again (after
 *    a first Apply too) and Output Messages says so.
 * It also gives the quality arrays MinAngle and MinDihedralAngle a fixed colour range
 * (0 to 60 and 0 to 70.5 degrees, the equilateral triangle's and the regular
 * tetrahedron's angles) through low-priority ParaView settings that user settings
 * override, and titles the histogram charts. For the restricted Delaunay filter it shows
 * one of its two histograms (the facet angles when there are no tetrahedra, else the
 * dihedral angles), and when a run gives no tetrahedra (an open surface, or Mesh Volume
 * off), the surface port instead of the empty tetrahedra.
 * It only acts in a builtin session (the GUI and the filters in one process).
 */

#ifndef pqGPUDelaunayGUI_h
#define pqGPUDelaunayGUI_h

#include <QObject>
#include <QPointer>
#include <QSet>

class pqPipelineSource;
class pqProxy;
class pqRepresentation;
class vtkAlgorithm;
class vtkObject;

class pqGPUDelaunayGUI : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  pqGPUDelaunayGUI(QObject* parent = nullptr);
  ~pqGPUDelaunayGUI() override = default;

  void startup();
  bool eventFilter(QObject* object, QEvent* event) override;
  void shutdown() {}

private Q_SLOTS:
  void onSourceAdded(pqPipelineSource* source);
  void onRepresentationAdded(pqRepresentation* representation);
  void onFilterStart(vtkObject* caller);
  void onFilterEnd(vtkObject* caller);
  void onProgress(const QString& text);
  void onAbort();

private:
  // Observes the start and end of the source's meshing filter; returns the filter, or
  // null when the source is not one of ours or its filter does not exist yet.
  vtkAlgorithm* Watch(pqPipelineSource* source);

  QSet<vtkObject*> Watched;             // filters whose start and end are observed
  vtkAlgorithm* Running = nullptr;     // the meshing filter executing now, if any
  QPointer<pqProxy> RunningProxy;
  bool InProcessEvents = false;

  Q_DISABLE_COPY(pqGPUDelaunayGUI)
};

#endif
