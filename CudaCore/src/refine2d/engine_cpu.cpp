#include "exec/cpu.h"
#include "refine2d/cdt_assembly.h"
#include "refine2d/input.h"
#include "refine2d/input_checks.h"

namespace gdr::r2d {

EngineResult refine_mesh_cpu(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb) {
  struct Trim {  // hand cached scratch memory back, also after an error
    ~Trim() { exec::Ops<exec::Cpu>::trim(); }
  } trim;
  return refine_mesh<exec::Cpu>(mesh, out, params, cb);
}

bool input_is_clean_cpu(const std::vector<Point2>& points, const std::vector<std::array<int, 2>>& segments) {
  return input_is_clean<exec::Cpu>(points, segments);
}

ParallelCdtResult parallel_cdt_cpu(const std::vector<double>& xy, const std::vector<int>& segments,
                                   bool hull, bool assemble, const std::vector<Point2>& seeds, int holes) {
  struct Trim {
    ~Trim() { exec::Ops<exec::Cpu>::trim(); }
  } trim;
  return parallel_cdt_assembled<exec::Cpu>(xy, segments, hull, assemble, seeds, holes);
}

}  // namespace gdr::r2d
