#include "exec/cpu.h"
#include "qm3d/engine_dispatch.h"

namespace gdr::qm3d {

EngineResult refine_mesh_cpu(const m3d::HostTetMesh& mesh, MeshResult& out,
                             const EngineParams& params, const Callbacks& cb,
                             m3d::HostTetMesh* final_mesh) {
  struct Trim {  // hand cached scratch memory back, also after an error
    ~Trim() { exec::Ops<exec::Cpu>::trim(); }
  } trim;
  return refine_mesh<exec::Cpu>(mesh, out, params, cb, final_mesh);
}

}  // namespace gdr::qm3d
