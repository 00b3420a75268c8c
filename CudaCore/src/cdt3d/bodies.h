// The bodies of a PLC: groups of its triangles that bound no domain cell in common (two parts
// side by side, a part inside another's cavity). Each is meshed alone where TetGen fails on
// them together (initial_cdt), and the meshes are merged into one in the PLC's numbering.
#pragma once
#include <vector>

#include "cdt3d/cdt3d.h"
#include "mesh3d/host_mesh.h"

namespace gdr::cdt3d {

struct Bodies {
  int count = 0;
  std::vector<int> of_triangle;  // per PLC triangle: its body
};
Bodies find_bodies(const Plc& plc);

// One body as a PLC of its own: its points (renumbered), triangles and segments; facet ids,
// cells and regions as in the whole PLC. With the maps back, and the seeds in its box.
struct BodyPlc {
  Plc plc;
  std::vector<int> point;    // body point -> PLC point
  std::vector<int> segment;  // body segment -> PLC segment
  std::vector<double> seeds;
};
BodyPlc body_plc(const Plc& plc, const Bodies& bodies, int body, const std::vector<double>& seeds);

// The meshes of all bodies (parts[b] of body b, numbered as its BodyPlc) as one mesh in the
// PLC's numbering: the PLC's points first, then each body's added points in turn.
// Subsegment bits and facet planes are left to the caller (mark_subsegments, ...).
m3d::HostTetMesh merge_bodies(const Plc& plc, const std::vector<BodyPlc>& bodies,
                              const std::vector<m3d::HostTetMesh>& parts);

}  // namespace gdr::cdt3d
