#include "gdr/backend.h"

#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <atomic>
#include <cctype>
#include <future>
#include <mutex>

#include "gdr/error.h"

#if defined(GDR_HAVE_CUDA)
#include <cuda_runtime_api.h>
#endif

namespace gdr {

const char* to_string(Backend b) {
  switch (b) {
    case Backend::Auto: return "auto";
    case Backend::Gpu: return "gpu";
    case Backend::Cpu: return "cpu";
  }
  return "?";
}

Backend backend_from_string(const std::string& name) {
  std::string s = name;
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  if (s == "auto") return Backend::Auto;
  if (s == "gpu" || s == "cuda") return Backend::Gpu;
  if (s == "cpu" || s == "openmp") return Backend::Cpu;
  throw Error(Status::InvalidInput, "unknown backend '" + name + "' (expected auto, gpu or cpu)");
}

static DeviceInfo query_device() {
  DeviceInfo info;
#if defined(GDR_HAVE_CUDA)
  int count = 0;  // cudaGetDeviceCount leaves it untouched when there is no driver
  cudaError_t e = cudaGetDeviceCount(&count);
  if (e != cudaSuccess || count == 0) {
    cudaGetLastError();
    info.reason = e != cudaSuccess ? std::string("no usable CUDA driver/device (") +
                                         cudaGetErrorString(e) + ")"
                                   : "no CUDA device";
    return info;
  }
  cudaDeviceProp prop{};
  if (cudaGetDeviceProperties(&prop, 0) != cudaSuccess) {
    cudaGetLastError();
    info.reason = "cannot query CUDA device 0";
    return info;
  }
  info.available = true;
  info.name = prop.name;
  info.total_memory = prop.totalGlobalMem;
#else
  info.reason = "this build has no CUDA backend";
#endif
  return info;
}

const DeviceInfo& device_info() {
  static const DeviceInfo info = query_device();
  return info;
}

bool gpu_available() { return device_info().available; }

Backend resolve_backend(Backend requested, std::size_t work_size, std::size_t gpu_min_work) {
  switch (requested) {
    case Backend::Cpu: return Backend::Cpu;
    case Backend::Gpu:
      if (!gpu_available())
        throw Error(Status::NoDevice, "GPU backend requested but " + device_info().reason);
      return Backend::Gpu;
    case Backend::Auto:
      if (work_size >= gpu_min_work && gpu_available()) return Backend::Gpu;
      return Backend::Cpu;
  }
  return Backend::Cpu;
}

int cpu_threads() { return omp_get_max_threads(); }

int cpu_threads_for(double tets) {
  static const double measured = std::getenv("GDR_TETS_PER_THREAD") ? std::atof(std::getenv("GDR_TETS_PER_THREAD")) : 0;
  const double per_thread = measured > 0 ? measured : 2500;  // the override: measurements of the rule itself
  return static_cast<int>(std::min(std::max(tets, 0.0) / per_thread + 1, 1e6));
}

std::string cpu_device_name(int threads) {
  return "CPU (" + std::to_string(threads) + (threads == 1 ? " OpenMP thread)" : " OpenMP threads)");
}

CpuThreadLimit::CpuThreadLimit(int n) : before_(omp_get_max_threads()) { set(n); }
void CpuThreadLimit::set(int n) {
  n = std::max(1, std::min(n, before_));
  most_ = std::max(most_, n);
  omp_set_num_threads(n);
}
CpuThreadLimit::~CpuThreadLimit() { omp_set_num_threads(before_); }

namespace {
std::atomic<bool> g_gpu_warm{false};
}
bool gpu_warm() { return g_gpu_warm.load(); }
void mark_gpu_warm() { g_gpu_warm.store(true); }

void prewarm_gpu(Backend backend, std::size_t work_size, std::size_t auto_min_work) {
#if defined(GDR_HAVE_CUDA)
  if (backend == Backend::Cpu || (backend == Backend::Auto && work_size < auto_min_work)) return;
  static std::once_flag once;
  std::call_once(once, [] {
    // The device query runs here, so that the CUDA runtime's own state exists before the
    // future below and is torn down after it: a process that exits at once waits for the
    // thread (the future's destructor) before CUDA shuts down.
    if (!device_info().available) return;
    static std::future<void> done = std::async(std::launch::async, [] { cudaFree(nullptr); });
  });
#else
  (void)backend, (void)work_size, (void)auto_min_work;
#endif
}

}  // namespace gdr
