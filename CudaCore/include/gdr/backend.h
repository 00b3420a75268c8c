// Run-time choice of execution space: the same kernels run on CUDA or on OpenMP.
#pragma once
#include <cstddef>
#include <string>

namespace gdr {

enum class Backend { Auto = 0, Gpu = 1, Cpu = 2 };

const char* to_string(Backend b);
Backend backend_from_string(const std::string& name);  // "auto" | "gpu" | "cpu"; throws InvalidInput

struct DeviceInfo {
  bool available = false;       // a CUDA device is usable from this process
  std::string name;             // e.g. "NVIDIA H100 80GB HBM3"
  std::size_t total_memory = 0; // bytes
  std::string reason;           // why not available (no driver, built without CUDA, ...)
};

// Queries the CUDA runtime once; safe on machines without a driver.
const DeviceInfo& device_info();
bool gpu_available();

// Resolves Auto: GPU when present and the work is large enough, else CPU (the GPU is not
// even probed for work below gpu_min_work). Throws Error(NoDevice) when Gpu is requested
// and none is usable.
Backend resolve_backend(Backend requested, std::size_t work_size = 0,
                        std::size_t gpu_min_work = 0);

// Whether this process has already run work on the GPU: the first GPU run pays for the CUDA
// context and for loading its kernels (about 0.35 s on the H100 machine), later runs do not.
bool gpu_warm();
void mark_gpu_warm();

// Starts creating the CUDA context in the background (once per process; nothing without
// CUDA or with `backend` Cpu, or for Auto when `work_size` is below `auto_min_work`), so that
// the device is ready when refinement starts instead of after the CPU's input checks and CDT.
void prewarm_gpu(Backend backend, std::size_t work_size, std::size_t auto_min_work);

int cpu_threads();  // OpenMP threads used by the CPU backend
std::string cpu_device_name(int threads);  // "CPU (N OpenMP threads)", a run's device_name

// gQM3d's CPU threads for a mesh of `tets` tetrahedra: one per 2,500 (GDR_TETS_PER_THREAD
// overrides it, for measurements). On the H200 machine's 16 threads, 3-5k tetrahedra
// refined in 0.11-0.31 s, against 0.05-0.17 s on one or two (and 30k in 0.10 s against
// 0.14 s on four): iterations that short do not share well.
int cpu_threads_for(double tets);

// For its lifetime, at most `n` OpenMP threads in the parallel loops this thread starts
// (small meshes: iterations too short to share among many threads). set() changes the
// limit as a mesh grows, never beyond the threads there were; most() is the largest set.
class CpuThreadLimit {
 public:
  explicit CpuThreadLimit(int n);
  ~CpuThreadLimit();
  void set(int n);
  int most() const { return most_; }
  CpuThreadLimit(const CpuThreadLimit&) = delete;
  CpuThreadLimit& operator=(const CpuThreadLimit&) = delete;

 private:
  int before_, most_ = 1;
};

}  // namespace gdr
