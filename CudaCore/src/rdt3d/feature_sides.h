// Sharp features the surface cuts across, mended by relabelling tetrahedra (host, after
// refinement, closed inputs).
//
// Next to an acute crease or a corner, every tetrahedron around a feature subsegment can have
// its circumcentre on one side of the surface, and the one restricted face there a dual that
// crosses the surface twice: the output surface then cuts the sharp edge off (README,
// "Restricted Delaunay: thin parts and features"). Refining there made it worse; CGAL Mesh_3
// prevents it with protecting balls. Here the tetrahedra around such a subsegment take the
// side of the input's solid right next to it instead: each is probed at a point inside it
// close to the subsegment, and where the probes inside form one run round the edge, the
// tetrahedra change side so that the surface passes through the subsegment. Where that
// pinches the surface (the changed ones meet the rest of their new side at an edge or a
// vertex only), their neighbours whose centroids lie on that side change too, up to three
// layers; where even that leaves a pinch, nothing changes. The triangulation stays as it
// is; the validator checks the surface that results.
#pragma once
#include <vector>

#include "rdt3d/kernels.h"

namespace gdr::rdt3d {

struct FeatureSides {
  long long lost = 0;        // feature subsegments no surface facet held
  long long mended = 0;      // of those, made edges of the surface by their own changes
  long long left = 0;        // feature subsegments no face of the output surface holds, at the end
  long long relabelled = 0;  // tetrahedra that changed side
  long long one_side = 0, wedges = 0, pinching = 0;  // left: probes all on one side, in several runs, a pinch made
};

// m: the final triangulation (no dead tetrahedra) with its flags; kInterior changes in place
// and `moved` (one per tetrahedron, zeroed by the caller) marks the tetrahedra that changed.
FeatureSides mend_lost_features(const m3d::TetView& m, const Criteria& c, const AabbView& tree,
                                std::vector<char>& moved);

}  // namespace gdr::rdt3d
