// VTK polydata (.vtp XML, .vtk legacy) as 2D input, in builds with VTK: read with VTK's
// readers and converted by the filters' converter (vtkGDRConversion::ToPslg), so that gdr 2d
// and the ParaView filter take the same lines and polygons as segments. That code is a module
// (libgdr_vtk_reader.so, vtk_reader_module.cpp) loaded only when such an input comes, so that
// gdr itself links no VTK. Without VTK these inputs are refused with a message that says why.
#pragma once
#include <string>

#include "gdr/pslg.h"

namespace gdr::cli {

// Whether `path` names polydata by its extension (.vtp or .vtk, any letter case).
bool is_vtk_polydata(const std::string& path);
// Throws gdr::Error (IoError) for a file VTK cannot read, or in a build without VTK.
// `warning` receives what the converter noted (input not in a z = constant plane).
Pslg read_vtk_pslg(const std::string& path, std::string& warning);

}  // namespace gdr::cli
