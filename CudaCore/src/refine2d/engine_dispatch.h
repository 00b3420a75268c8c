// The engines' two instantiations: engine_cpu.cpp (OpenMP) and engine_cuda.cu (CUDA).
#pragma once
#include <memory>

#include "refine2d/cdt_engine.h"
#include "refine2d/engine.h"
#include "refine2d/thin_parts.h"

namespace gdr::r2d {

EngineResult refine_mesh_cpu(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb);
#if defined(GDR_HAVE_CUDA)
EngineResult refine_mesh_cuda(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                             const Callbacks& cb);
void trim_device_memory_cuda();  // cached device memory back to the driver
#endif

// An initial CDT assembled in the memory of the space that computed it, ready for that
// space's engine (cdt_assembly.h): what refine_2d needs of it before the refinement, or
// the host's copy where the refinement runs elsewhere.
class PreparedCdt {
 public:
  virtual ~PreparedCdt() = default;
  virtual int points() const = 0;
  virtual int triangles() const = 0;
  struct Areas {
    double area = 0;     // the domain's, scaled units
    double bounded = 0;  // the triangles the area bounds ask for (estimate_size)
  };
  // `region_area2`: twice each region's area bound by region number - 1 (EngineParams).
  virtual Areas areas(double max_area, const std::vector<double>& region_area2) = 0;
  virtual ThinEstimate thin_parts(double tan_theta, double max_width) = 0;  // thin_parts.h
  virtual HostMesh download() = 0;
  // Refines in the space (once: the mesh moves into the engine).
  virtual EngineResult refine(MeshResult& out, const EngineParams& params, const Callbacks& cb) = 0;
};

// The parallel CDT (cdt_engine.h) of xy (the points, then the bounding triangle's three
// corners) and the input segments (2 per segment), with the convex hull's edges when
// `hull`: assembled in the space when `assemble` and it can be (`prepared`; `seeds`: the
// first `holes` are hole seeds, the rest region seeds), else as `raw` triangles for the
// host's assemble_cdt.
struct ParallelCdtResult {
  std::unique_ptr<PreparedCdt> prepared;
  RawCdt raw;
  std::vector<PhaseTime> phases;
};
ParallelCdtResult parallel_cdt_cpu(const std::vector<double>& xy, const std::vector<int>& segments,
                                   bool hull, bool assemble, const std::vector<Point2>& seeds, int holes);
#if defined(GDR_HAVE_CUDA)
ParallelCdtResult parallel_cdt_cuda(const std::vector<double>& xy, const std::vector<int>& segments,
                                    bool hull, bool assemble, const std::vector<Point2>& seeds, int holes);
#endif

}  // namespace gdr::r2d
