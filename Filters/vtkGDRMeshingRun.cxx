#include "vtkGDRMeshingRun.h"

#include "vtkAlgorithm.h"
#include "vtkErrorCode.h"
#include "vtkObject.h"
#include "vtkOutputWindow.h"
#include "vtkSetGet.h"

#include "gdr/error.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <new>
#include <string>

namespace
{
// vtkAlgorithm::SetErrorCode is protected; a member pointer taken through a derived class
// reaches it for any algorithm, so that this one helper sets it for every filter.
struct ErrorCodeAccess : vtkAlgorithm
{
  static void Set(vtkAlgorithm* algorithm, unsigned long code)
  {
    (algorithm->*(&ErrorCodeAccess::SetErrorCode))(code);
  }
};
}

//------------------------------------------------------------------------------
vtkGDRMeshingRun::vtkGDRMeshingRun(vtkAlgorithm* filter)
  : Filter(filter)
{
  ErrorCodeAccess::Set(this->Filter, vtkErrorCode::NoError);
}

//------------------------------------------------------------------------------
void vtkGDRMeshingRun::Failed()
{
  // Scripts tell a failed run from an empty result by the error code (gpudelaunay's
  // update helpers raise on it).
  ErrorCodeAccess::Set(this->Filter, vtkErrorCode::UserError);
}

//------------------------------------------------------------------------------
bool vtkGDRMeshingRun::SelectBackend(int requested, gdr::Backend& backend)
{
  switch (requested)
  {
    case 1: // GPU
      if (!gdr::gpu_available())
      {
        vtkErrorWithObjectMacro(this->Filter,
          << "Backend is GPU but no usable CUDA device was found ("
            << gdr::device_info().reason << "). Choose Auto or CPU.");
        this->Failed();
        return false;
      }
      backend = gdr::Backend::Gpu;
      return true;
    case 2: // CPU
      backend = gdr::Backend::Cpu;
      return true;
    default: // Auto
      if (!gdr::gpu_available())
      {
        // Expected on a machine without a GPU: information, said once per session, not a
        // warning on every run.
        static std::atomic<bool> said{ false };
        if (!said.exchange(true))
        {
          const std::string text = "GPU meshing: no usable CUDA device (" +
            gdr::device_info().reason + "); the meshing filters run on the CPU backend.\n";
          vtkOutputWindow::GetInstance()->DisplayText(text.c_str());
        }
        backend = gdr::Backend::Cpu;
      }
      else
      {
        backend = gdr::Backend::Auto; // the engine picks the GPU for large enough inputs
      }
      return true;
  }
}

//------------------------------------------------------------------------------
gdr::Callbacks vtkGDRMeshingRun::GetCallbacks()
{
  gdr::Callbacks callbacks;
  vtkAlgorithm* filter = this->Filter;
  callbacks.progress = [filter](double fraction, const std::string& phase)
  {
    filter->SetProgressText(phase.empty() ? nullptr : phase.c_str());
    filter->UpdateProgress(std::min(1.0, std::max(0.0, fraction)));
  };
  callbacks.abort = [filter]() { return filter->CheckAbort(); };
  callbacks.warning = [filter](const std::string& message)
  { vtkWarningWithObjectMacro(filter, << message); };
  return callbacks;
}

//------------------------------------------------------------------------------
bool vtkGDRMeshingRun::Execute(const std::function<void()>& work)
{
  try
  {
    work();
    return true;
  }
  catch (const gdr::Error& e)
  {
    if (e.status() == gdr::Status::Aborted)
    {
      this->Aborted = true;
      this->Filter->SetAbortOutput(true);
      return false;
    }
    vtkErrorWithObjectMacro(this->Filter, << gdr::to_string(e.status()) << ": " << e.what());
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorWithObjectMacro(this->Filter, << "Out of memory while meshing.");
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(this->Filter, << "Meshing failed: " << e.what());
  }
  catch (...)
  {
    vtkErrorWithObjectMacro(this->Filter, << "Meshing failed with an unknown error.");
  }
  this->Failed();
  return false;
}
