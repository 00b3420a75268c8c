// The engine's two instantiations: engine_cpu.cpp (OpenMP) and engine_cuda.cu (CUDA).
#pragma once
#include "refine2d/engine.h"

namespace gdr::r2d {

EngineResult refine_mesh_cpu(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb);
#if defined(GDR_HAVE_CUDA)
EngineResult refine_mesh_cuda(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb);
#endif

}  // namespace gdr::r2d
