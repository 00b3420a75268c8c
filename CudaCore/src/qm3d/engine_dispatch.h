// The engine's two instantiations: engine_cpu.cpp (OpenMP) and engine_cuda.cu (CUDA).
#pragma once
#include "qm3d/engine.h"

namespace gdr::qm3d {

// GDR_DISABLE's strategies switched off (quality_tet_mesh.cpp); all on without it.
Strategies strategies_from_environment();

EngineResult refine_mesh_cpu(const m3d::HostTetMesh& mesh, MeshResult& out,
                             const EngineParams& params, const Callbacks& cb,
                             m3d::HostTetMesh* final_mesh = nullptr);
#if defined(GDR_HAVE_CUDA)
EngineResult refine_mesh_cuda(const m3d::HostTetMesh& mesh, MeshResult& out,
                              const EngineParams& params, const Callbacks& cb,
                             m3d::HostTetMesh* final_mesh = nullptr);
#endif

}  // namespace gdr::qm3d
