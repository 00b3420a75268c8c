// Per-triangle arrays written with a 2D mesh (names as in ARCHITECTURE.md).
#pragma once
#include "gdr/io.h"
#include "gdr/pslg.h"

namespace gdr::cli {

// Cell data: MinAngle, MaxAngle (degrees), RadiusEdgeRatio, Area, IsBad (min angle below
// `min_angle_deg`; all 0 when the bound is 0). The VTK writers add PointType themselves.
io::Attributes triangle_attributes(const TriMesh& mesh, double min_angle_deg);

}  // namespace gdr::cli
