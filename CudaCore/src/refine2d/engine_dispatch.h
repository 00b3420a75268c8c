// The engines' two instantiations: engine_cpu.cpp (OpenMP) and engine_cuda.cu (CUDA).
#pragma once
#include "refine2d/cdt_engine.h"
#include "refine2d/engine.h"

namespace gdr::r2d {

EngineResult refine_mesh_cpu(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb);
RawCdt parallel_cdt_cpu(const std::vector<double>& xy, const std::vector<int>& segments, bool hull);
#if defined(GDR_HAVE_CUDA)
EngineResult refine_mesh_cuda(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb);
RawCdt parallel_cdt_cuda(const std::vector<double>& xy, const std::vector<int>& segments, bool hull);
void trim_device_memory_cuda();  // cached device memory back to the driver
#endif

}  // namespace gdr::r2d
