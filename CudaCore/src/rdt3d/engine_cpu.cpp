#include "exec/cpu.h"
#include "rdt3d/engine_dispatch.h"

namespace gdr::rdt3d {

EngineResult refine_restricted_cpu(const m3d::HostTetMesh& mesh, const SurfaceInput& surface,
                                   MeshResult& out, const EngineParams& params, const Callbacks& cb) {
  struct Trim {  // hand cached scratch memory back, also after an error
    ~Trim() { exec::Ops<exec::Cpu>::trim(); }
  } trim;
  return refine_restricted<exec::Cpu>(mesh, surface, out, params, cb);
}

}  // namespace gdr::rdt3d
