/**
 * @class   vtkGDRMeshingRun
 * @brief   shared run support of the GPU meshing filters (private, not wrapped)
 *
 * One object per RequestData call. It maps the filter's Backend property to the
 * engine's choice (AUTO falls back to the CPU with a warning when no GPU is usable,
 * GPU without a device is an error), builds the engine callbacks (progress through
 * UpdateProgress, abort through CheckAbort, engine notes as warnings) and runs the
 * engine call, mapping gdr::Error and any other exception to vtkErrorMacro.
 * All three meshing filters and the readers use it the same way. It resets the
 * algorithm's error code when constructed and sets it to vtkErrorCode::UserError when it
 * reports a failure, so that scripts can tell a failed run from an empty result.
 */

#ifndef vtkGDRMeshingRun_h
#define vtkGDRMeshingRun_h

#include "gdr/backend.h"
#include "gdr/progress.h"

#include <functional>

class vtkAlgorithm;

class vtkGDRMeshingRun
{
public:
  explicit vtkGDRMeshingRun(vtkAlgorithm* filter);

  /**
   * Resolves the filter's Backend property (0 Auto, 1 GPU, 2 CPU). Returns false after
   * reporting an error when the GPU is requested and none is usable.
   */
  bool SelectBackend(int requested, gdr::Backend& backend);

  /**
   * Callbacks for the engine: progress -> UpdateProgress / SetProgressText,
   * abort -> CheckAbort, warning -> vtkWarningMacro.
   */
  gdr::Callbacks GetCallbacks();

  /**
   * Runs the engine call. Returns true on success. On failure the error has been
   * reported (except for an abort, which is silent) and false is returned.
   */
  bool Execute(const std::function<void()>& work);

  /**
   * True when the run stopped because the user aborted it.
   */
  bool WasAborted() const { return this->Aborted; }

private:
  void Failed();

  vtkAlgorithm* Filter;
  bool Aborted = false;
};

#endif
// VTK-HeaderTest-Exclude: vtkGDRMeshingRun.h
