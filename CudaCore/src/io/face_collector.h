// Collects the faces of a surface file into a Surface: triangles as they are, larger
// polygons ear clipped in their plane into triangles of one facet. Surface::triangle_facet
// (the face id of each triangle) is filled once some face had more than three corners.
#pragma once
#include <vector>

#include "gdr/pslg.h"
#include "io/text_file.h"

namespace gdr::io {

class FaceCollector {
 public:
  explicit FaceCollector(Surface& surface) : surface_(surface) {}

  // Adds face `id` (its corners: indices into surface.points, already range checked).
  // Returns false when a polygon cannot be triangulated (degenerate or not simple).
  bool add(const std::vector<int>& corners, int id) {
    if (corners.size() == 3) {
      surface_.triangles.push_back({corners[0], corners[1], corners[2]});
    } else {
      polygons_ = true;
      if (!triangulate_polygon(surface_.points, corners, surface_.triangles)) return false;
    }
    facet_.resize(surface_.triangles.size(), id);
    return true;
  }

  // Call once after the last face.
  void finish() {
    if (polygons_) surface_.triangle_facet = facet_;
  }

 private:
  Surface& surface_;
  std::vector<int> facet_;
  bool polygons_ = false;
};

}  // namespace gdr::io
