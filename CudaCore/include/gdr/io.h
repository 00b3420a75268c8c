// Readers and writers for the formats users already have. Malformed files throw
// gdr::Error(Status::IoError, "FILE:LINE: reason"); they never crash.
#pragma once
#include <string>
#include <vector>

#include "gdr/pslg.h"

namespace gdr::io {

// Triangle .poly (points with their attributes and boundary markers, segments with their
// markers, holes, regional attributes and area constraints; 0- or 1-based as the file
// says). A .poly whose point section is empty takes its points from the .node file beside
// it. Also reads .node.
Pslg read_poly(const std::string& path);
// The files read_poly(path) may read: `path`, and for a .poly the .node beside it.
std::vector<std::string> poly_input_files(const std::string& path);

// Triangle .node/.ele as a TriMesh (point attributes and markers, the triangles' first
// attribute as triangle_region). A .poly with no points beside the .ele (same base name,
// as write_triangle writes it) gives the subsegments and their boundary markers
// (subsegment_markers; subsegment_source stays empty).
TriMesh read_triangle_mesh(const std::string& node_path, const std::string& ele_path);

// Surfaces. Faces with more than three corners are ear clipped in their plane into
// triangles of one facet: Surface::triangle_facet then holds each triangle's face (facet)
// number, 0-based in file order; it stays empty when every face is a triangle.
//
// TetGen .poly / .smesh: every facet's polygons are triangulated into that facet
// (2-corner polygons become Surface::segments); the volume hole list and the region list
// ("x y z attribute [max volume]") fill Surface::holes and Surface::regions. Facet holes
// are refused with an IoError.
Surface read_tetgen_poly(const std::string& path);
Surface read_off(const std::string& path);
Surface read_stl(const std::string& path);   // ASCII or binary; identical vertices merged
// PLY, ASCII or binary (either byte order): vertex x, y, z of any numeric type, the face
// list "vertex_indices" (or "vertex_index") of any integer types; other data skipped.
Surface read_ply(const std::string& path);
// Wavefront OBJ: "v" and "f" lines (corners "i", "i/t", "i//n", "i/t/n"; negative indices
// count back from the last vertex read); everything else skipped.
Surface read_obj(const std::string& path);
// Any of the surface formats above, by extension, in any letter case (.off, .stl, .ply,
// .obj, .poly, .smesh). A TetGen .node gives its points alone (no facets).
Surface read_surface(const std::string& path);
// The files read_surface(path) may read: `path`, and for a .poly or .smesh the .node beside
// it (where a file whose point section is empty takes its points from).
std::vector<std::string> surface_input_files(const std::string& path);

// TetGen .node/.ele (4 or 10 nodes per tetrahedron, the first 4 used) as a TetMesh, with the
// .face beside the .ele, when there is one, as subfaces. TetGen files store tetrahedra with
// orient3d < 0; they are read (and written by write_tetgen) with two corners swapped so that
// TetMesh tetrahedra are positive (orient3d > 0) as gdr/validate.h defines.
TetMesh read_tetgen_mesh(const std::string& node_path, const std::string& ele_path);

// Reads any supported input by extension: .poly and .node (2D Triangle or 3D TetGen by the
// dimension in their header), .off, .stl, .ply, .obj, .smesh.
enum class InputKind { Pslg2d, Surface3d };
InputKind detect_input_kind(const std::string& path);
// 2 for a Triangle .ele (3 or 6 nodes per triangle), 3 for a TetGen .ele (4 or 10 per
// tetrahedron), from its header.
int element_file_dimension(const std::string& ele_path);

// Named per-element arrays attached to an output file.
struct DataArray {
  std::string name;
  int components = 1;
  std::vector<double> values;  // size = components * count
  bool float32 = false;        // written in single precision (half the bytes of a large file)
};

struct Attributes {
  std::vector<DataArray> point_data;
  std::vector<DataArray> cell_data;
};

// VTK XML (.vtu unstructured grid, .vtp polydata), written by the core itself so the
// core-only build (e.g. the GPU machine) writes results too. A TriMesh's file also carries
// what the mesh has of Triangle's data: the cell array Region (triangle_region), the point
// arrays BoundaryMarker (point_markers) and PointAttributes (point_attributes).
void write_vtu(const std::string& path, const TriMesh& mesh, const Attributes& attributes = {});
void write_vtp(const std::string& path, const TriMesh& mesh, const Attributes& attributes = {});
// Legacy VTK (.vtk, binary polydata), for tools that read only that: the same arrays as
// write_vtp, as FIELD arrays of doubles.
void write_vtk_legacy(const std::string& path, const TriMesh& mesh, const Attributes& attributes = {});
// A TetMesh's .vtu also carries the point array PointType and, when the mesh has regions,
// the cell array Region (its tet_region).
void write_vtu(const std::string& path, const TetMesh& mesh, const Attributes& attributes = {});

// The surface of a TetMesh (its subfaces, on its points: the restricted mesher's surface) as
// VTK XML polydata, with PointType and the caller's per-triangle arrays; write_surface picks
// .vtp or .off (points and triangles only) by the extension.
void write_surface_vtp(const std::string& path, const TetMesh& mesh, const Attributes& attributes = {});
void write_surface(const std::string& path, const TetMesh& mesh, const Attributes& attributes = {});

// Triangle .node/.ele (+ .poly of subsegments), numbered from the mesh's first_index, with
// point attributes and boundary markers in the .node, the regional attribute in the .ele and
// the subsegments' boundary markers in the .poly, as Triangle writes them; TetGen
// .node/.ele/.face, the .face with the
// subfaces' input facet ids (subface_facet) as boundary markers when the mesh has them.
// `base` has no extension.
void write_triangle(const std::string& base, const TriMesh& mesh);
void write_tetgen(const std::string& base, const TetMesh& mesh);
// Medit .mesh (MeshVersionFormatted 2, Dimension 3): Vertices with the point type as
// reference, Tetrahedra with the region attribute (1 without regions), Triangles (the
// subfaces) with the input facet id + 1 (0 where unknown).
void write_medit(const std::string& path, const TetMesh& mesh);

// Writes by the extension of `path`: .vtu, .vtp, .vtk, .node or .ele (Triangle files beside it).
void write_mesh(const std::string& path, const TriMesh& mesh, const Attributes& attributes = {});
// A TetMesh by .vtu, .mesh (Medit), or .node, .ele or .face (TetGen's three files).
void write_mesh(const std::string& path, const TetMesh& mesh, const Attributes& attributes = {});
// The files write_mesh(path, TriMesh) writes: `path`, or for .node/.ele Triangle's three,
// BASE.node, BASE.ele and BASE.poly.
std::vector<std::string> trimesh_output_files(const std::string& path);
// The files write_mesh(path, TetMesh) writes: `path`, or for .node/.ele/.face TetGen's three.
std::vector<std::string> tetmesh_output_files(const std::string& path);

// Every writer above writes atomically: each file goes to a temporary file in its folder,
// flushed to disk, and is renamed into place once all files of the set are complete. An
// error or a crash leaves an existing output as it was or replaced by a complete new one,
// never half written (only a crash between the renames of a set can mix old and new files).
// For any other output (statistics, reports):
void write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace gdr::io
