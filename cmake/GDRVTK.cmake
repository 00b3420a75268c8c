# VTK module (Filters/), Python package `gpudelaunay` and ParaView plugin (Plugin/).
# Included from the top-level CMakeLists.txt once ParaView 5.11 has been found.
include(GNUInstallDirs)

# The plugin's GUI part links ParaView's Qt libraries, whose link interfaces name Qt, X11,
# GLEW and other packages: found here, in the scope where ParaView's targets were imported.
if(PARAVIEW_USE_QT)
  find_package(ParaView QUIET COMPONENTS pqComponents)
  list(APPEND CMAKE_MODULE_PATH "${VTK_DIR}")  # VTK's own Find modules (NetCDF, GLEW...)
  find_package(Qt5 QUIET COMPONENTS OpenGL)
  foreach(_gdr_package IN ITEMS X11 GLEW LibXml2 Boost NetCDF)
    find_package(${_gdr_package} QUIET)
  endforeach()
  find_package(HDF5 QUIET COMPONENTS C HL)
endif()

# Shared libraries: the ParaView plugin and the Python package load one and the same
# filter library (VTK's module and plugin functions follow BUILD_SHARED_LIBS).
set(_gdr_saved_build_shared_libs "${BUILD_SHARED_LIBS}")
set(BUILD_SHARED_LIBS ON)

# --- VTK module ---------------------------------------------------------------
vtk_module_scan(
  MODULE_FILES     "${PROJECT_SOURCE_DIR}/Filters/vtk.module"
  REQUEST_MODULES  GPUDelaunay::GPUDelaunayFilters
  PROVIDES_MODULES gdr_vtk_modules
  HIDE_MODULES_FROM_CACHE ON)

vtk_module_build(
  MODULES             ${gdr_vtk_modules}
  PACKAGE             GPUDelaunay
  ENABLE_WRAPPING     ON
  INSTALL_HEADERS     OFF
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  RUNTIME_DESTINATION "${CMAKE_INSTALL_BINDIR}"
  ARCHIVE_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  CMAKE_DESTINATION   "${CMAKE_INSTALL_LIBDIR}/cmake/GPUDelaunay")

# gdr 2d reads .vtp/.vtk polydata through the filters' converter (apps/gdr/vtk_input.cpp),
# so that the CLI and the filter take the same lines and polygons as segments.
# That code is a module gdr loads only for such inputs (apps/gdr/vtk_input.h): VTK's
# libraries cost every run 25 ms of loading otherwise.
add_library(gdr_vtk_reader MODULE "${PROJECT_SOURCE_DIR}/apps/gdr/vtk_reader_module.cpp")
target_include_directories(gdr_vtk_reader PRIVATE "${PROJECT_SOURCE_DIR}/Filters" "${PROJECT_SOURCE_DIR}/CudaCore/include")
target_link_libraries(gdr_vtk_reader PRIVATE GPUDelaunay::GPUDelaunayFilters VTK::IOXML VTK::IOLegacy)
set_target_properties(gdr_vtk_reader PROPERTIES CXX_VISIBILITY_PRESET hidden)
target_compile_definitions(gdr PRIVATE GDR_CLI_HAVE_VTK=1)
target_link_libraries(gdr PRIVATE ${CMAKE_DL_LIBS})
add_dependencies(gdr gdr_vtk_reader)

# --- Python package `gpudelaunay` ----------------------------------------------
# Build tree: <build>/python/gpudelaunay; set PYTHONPATH=<build>/python.
find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
set(GDR_PYTHON_DESTINATION "python" CACHE STRING
  "Where the gpudelaunay Python package goes (relative to the build and install prefix)")
mark_as_advanced(GDR_PYTHON_DESTINATION)
vtk_module_wrap_python(
  MODULES            ${gdr_vtk_modules}
  TARGET             GPUDelaunay::Python
  PYTHON_PACKAGE     gpudelaunay
  MODULE_DESTINATION "${GDR_PYTHON_DESTINATION}"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  CMAKE_DESTINATION  "${CMAKE_INSTALL_LIBDIR}/cmake/GPUDelaunay"
  INSTALL_HEADERS    OFF
  BUILD_STATIC       OFF)

# The package's __init__: OpenMP's short spin unless the user chose (as gdr does in
# apps/gdr/main.cpp; libgomp reads it when it loads, with the wrapped classes, unless
# something imported before has loaded it), VTK's base modules, the wrapped classes, then
# the NumPy API (Python/gpudelaunay: refine_2d, MeshingError, ...).
set(_gdr_python_package "${CMAKE_BINARY_DIR}/${GDR_PYTHON_DESTINATION}/gpudelaunay")
set(_gdr_python_init "${_gdr_python_package}/__init__.py")
file(GENERATE OUTPUT "${_gdr_python_init}" CONTENT
"\"\"\"GPU Delaunay mesh refinement for VTK (vtkGPUConstrainedDelaunay2D,
vtkGPUQualityTetMesh, vtkGPURestrictedDelaunay3D) and NumPy (refine_2d).\"\"\"
import os
if not (os.environ.get('OMP_WAIT_POLICY') or os.environ.get('GOMP_SPINCOUNT')):
    os.environ['GOMP_SPINCOUNT'] = '10000'  # threads that share the cores (README, Backends)
import vtkmodules.vtkCommonExecutionModel  # noqa: E402,F401  (base classes)
from .GPUDelaunayFilters import *  # noqa: E402,F401,F403
from .meshing import (MeshingError, MeshingWarning, MeshResult, refine_2d,  # noqa: E402,F401
                      update, update_pipeline)
")
configure_file("${PROJECT_SOURCE_DIR}/Python/gpudelaunay/meshing.py"
               "${_gdr_python_package}/meshing.py" COPYONLY)
install(FILES "${_gdr_python_init}" "${_gdr_python_package}/meshing.py"
        DESTINATION "${GDR_PYTHON_DESTINATION}/gpudelaunay")

# --- ParaView plugin GPUDelaunayRefinement ---------------------------------------
paraview_plugin_scan(
  PLUGIN_FILES      "${PROJECT_SOURCE_DIR}/Plugin/paraview.plugin"
  PROVIDES_PLUGINS  gdr_paraview_plugins
  ENABLE_BY_DEFAULT ON
  HIDE_PLUGINS_FROM_CACHE ON)

set(GDR_PLUGIN_SUBDIR "paraview-${ParaView_VERSION_MAJOR}.${ParaView_VERSION_MINOR}/plugins")
paraview_plugin_build(
  PLUGINS             ${gdr_paraview_plugins}
  RUNTIME_DESTINATION "${CMAKE_INSTALL_BINDIR}"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  LIBRARY_SUBDIRECTORY "${GDR_PLUGIN_SUBDIR}"
  AUTOLOAD            GPUDelaunayRefinement
  ADD_INSTALL_RPATHS  ON)

# Where tests and scripts find the built pieces.
set(GDR_PLUGIN_DIR "${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR}/${GDR_PLUGIN_SUBDIR}/GPUDelaunayRefinement")
set(GDR_PYTHON_DIR "${CMAKE_BINARY_DIR}/${GDR_PYTHON_DESTINATION}")

set(BUILD_SHARED_LIBS "${_gdr_saved_build_shared_libs}")
