// Parallel (TBB) instantiation of the Mesh_3 baseline.
#include <stdexcept>

#include "mesh3_run.h"

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <memory>

#include "mesh3_impl.h"
#endif

namespace gdr_bench {

Mesh3Result run_mesh3_parallel(const gdr::Surface& surface, const Mesh3Params& params) {
#ifdef CGAL_LINKED_WITH_TBB
  std::unique_ptr<tbb::global_control> limit;
  if (params.threads > 0) {
    limit = std::make_unique<tbb::global_control>(
        tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(params.threads));
  }
  Mesh3Result r = run_mesh3<CGAL::Parallel_tag>(surface, params);
  r.threads = static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  return r;
#else
  (void)surface;
  (void)params;
  throw std::runtime_error("bench_cgal_mesh3 was built without TBB: no parallel run");
#endif
}

}  // namespace gdr_bench
