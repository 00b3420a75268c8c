// Per-element arrays written with a 2D or 3D mesh (names as in ARCHITECTURE.md).
#pragma once
#include "gdr/io.h"
#include "gdr/pslg.h"
#include "gdr/qm3d.h"

namespace gdr::cli {

// Cell data: MinAngle, MaxAngle (degrees), RadiusEdgeRatio, Area, IsBad (min angle below
// `min_angle_deg`; all 0 when the bound is 0). The VTK writers add PointType themselves.
io::Attributes triangle_attributes(const TriMesh& mesh, double min_angle_deg);

// Cell data of a quality tetrahedral mesh, as the mesher measured it: RadiusEdgeRatio,
// MinDihedralAngle, MaxDihedralAngle (degrees), Volume, IsBad (1 above the bounds, 2 above
// them but protected: next to small input angles). The .vtu writer adds PointType and Region.
io::Attributes tet_attributes(const QualityTetResult& result);

}  // namespace gdr::cli
