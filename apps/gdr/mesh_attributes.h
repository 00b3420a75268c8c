// Per-triangle and per-point arrays written with a 2D mesh (names as in ARCHITECTURE.md).
#pragma once
#include "gdr/io.h"
#include "gdr/pslg.h"

namespace gdr::cli {

// Cell data: MinAngle, MaxAngle (degrees), RadiusEdgeRatio, Area, IsBad (min angle below
// `min_angle_deg`; all 0 when the bound is 0). Point data: PointType (0 input, 1 on a
// segment, 2 free) when the mesh has point types.
io::Attributes triangle_attributes(const TriMesh& mesh, double min_angle_deg);

}  // namespace gdr::cli
