// Sharp features of gDP3d's input (host): the input edges the output must keep, chained into
// polylines between corners. A feature edge is an input segment, a boundary edge of an open
// surface, or an edge whose two triangles turn by more than the feature angle (their normals
// make an angle above it: 0 for a flat surface). Corners are the feature vertices where the
// polylines end, branch or turn by more than the feature angle.
#pragma once
#include <array>
#include <vector>

#include "cdt3d/cdt3d.h"

namespace gdr::rdt3d {

struct Features {
  std::vector<std::array<int, 2>> edges;  // feature edges (Plc point ids)
  std::vector<unsigned char> kind;        // per Plc point: kNotFeature, kOnFeature or kCorner
  long long corners = 0;
};
enum : unsigned char { kNotFeature = 0, kOnFeature = 1, kCorner = 2 };

// `feature_angle_deg` <= 0 detects none: only the input segments are features then; above
// 0 the edges come from plc.edges (CheckOptions::keep_edges).
// `input_segments`: the input's segments, as Plc point ids (triangle edges: check_surface).
Features find_features(const cdt3d::Plc& plc, const std::vector<std::array<int, 2>>& input_segments,
                       double feature_angle_deg);

}  // namespace gdr::rdt3d
