// Sequential instantiation of the Mesh_3 baseline.
#include "mesh3_impl.h"

namespace gdr_bench {

Mesh3Result run_mesh3_sequential(const gdr::Surface& surface, const Mesh3Params& params) {
  return run_mesh3<CGAL::Sequential_tag>(surface, params);
}

}  // namespace gdr_bench
