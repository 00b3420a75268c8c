#include "exec/cpu.h"
#include "refine2d/engine_dispatch.h"

namespace gdr::r2d {

EngineResult refine_mesh_cpu(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb) {
  struct Trim {  // hand cached scratch memory back, also after an error
    ~Trim() { exec::Ops<exec::Cpu>::trim(); }
  } trim;
  return refine_mesh<exec::Cpu>(mesh, out, params, cb);
}

}  // namespace gdr::r2d
