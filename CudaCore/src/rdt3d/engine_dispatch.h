// The engine's two instantiations: engine_cpu.cpp (OpenMP) and engine_cuda.cu (CUDA).
#pragma once
#include "rdt3d/engine.h"

namespace gdr::rdt3d {

EngineResult refine_restricted_cpu(const m3d::HostTetMesh& mesh, const SurfaceInput& surface,
                                   MeshResult& out, const EngineParams& params, const Callbacks& cb);
#if defined(GDR_HAVE_CUDA)
EngineResult refine_restricted_cuda(const m3d::HostTetMesh& mesh, const SurfaceInput& surface,
                                    MeshResult& out, const EngineParams& params, const Callbacks& cb);
#endif

}  // namespace gdr::rdt3d
