#include "exec/cuda.cuh"
#include "refine2d/cdt_assembly.h"
#include "refine2d/input.h"
#include "refine2d/input_checks.h"

namespace gdr::r2d {

EngineResult refine_mesh_cuda(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb) {
  struct Trim {  // hand cached scratch memory back, also after an error
    ~Trim() { exec::Ops<exec::Cuda>::trim(); }
  } trim;
  return refine_mesh<exec::Cuda>(mesh, out, params, cb);
}

// The pool keeps the CDT's memory for the refinement that follows (refine_2d hands it back
// when the run ends, trim_device_memory_cuda); after an error it is handed back at once.
ParallelCdtResult parallel_cdt_cuda(const std::vector<double>& xy, const std::vector<int>& segments,
                                    bool hull, bool assemble, const std::vector<Point2>& seeds, int holes) {
  try {
    return parallel_cdt_assembled<exec::Cuda>(xy, segments, hull, assemble, seeds, holes);
  } catch (...) {
    exec::Ops<exec::Cuda>::trim();
    throw;
  }
}

bool input_is_clean_cuda(const std::vector<Point2>& points, const std::vector<std::array<int, 2>>& segments) {
  return input_is_clean<exec::Cuda>(points, segments);
}

void trim_device_memory_cuda() { exec::Ops<exec::Cuda>::trim(); }

}  // namespace gdr::r2d
