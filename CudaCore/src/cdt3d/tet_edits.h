// Edits of the initial CDT after TetGen, before refinement.
#pragma once
#include <vector>

#include "cdt3d/cdt3d.h"
#include "mesh3d/host_mesh.h"

namespace gdr::cdt3d {

// Tetrahedra of zero or negative volume (exact orient3d) with two faces on the boundary,
// subfaces of one facet, and two towards the domain: dropped, their inner faces becoming the
// facet's subfaces (see the .cpp). Returns how many.
int drop_flat_boundary_tets(const Plc& plc, m3d::HostTetMesh& m);

// Removes the tetrahedra marked in `dead` and renumbers every link to the others.
void remove_tets(m3d::HostTetMesh& m, const std::vector<char>& dead);

}  // namespace gdr::cdt3d
