// Consistent orientation of a triangulated surface (host).
//
// gDP3d orients a facet of a surface-only mesh along the normal of the input triangle its
// dual meets. Where the input folds sharply (a scan's crease, a fin), neighbouring facets
// meet different input triangles and can come out facing opposite ways. Here the triangles
// are grouped into patches joined across manifold edges (exactly two triangles), each patch
// made consistent, and turned the way most of its vote weight says.
#pragma once
#include <vector>

namespace gdr::m3d {

struct OrientVote {
  double weight = 0;     // confidence in the triangle's present orientation (area x cosine)
  bool certain = false;  // the orientation is known (it bounds a volume): outweighs any weight
};

struct OrientResult {
  long long flipped = 0;        // triangles turned
  long long patches = 0;        // patches of triangles joined across manifold edges
  long long non_orientable = 0; // manifold edges whose two triangles could not agree
};

// tri: 3 corners per triangle, reordered in place. votes: one per triangle.
OrientResult orient_consistently(std::vector<int>& tri, const std::vector<OrientVote>& votes);

}  // namespace gdr::m3d
