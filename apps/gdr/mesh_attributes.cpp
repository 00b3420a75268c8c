#include "mesh_attributes.h"

#include "gdr/validate.h"

namespace gdr::cli {

io::Attributes triangle_attributes(const TriMesh& mesh, double min_angle_deg) {
  const long long n = static_cast<long long>(mesh.triangles.size());
  // Angles, ratios and flags in single precision (plenty to look at, and a file of 10M
  // triangles smaller by 160 MB); areas in double, as tiny as the input's units make them.
  io::DataArray min_angle{"MinAngle", 1, std::vector<double>(n), true};
  io::DataArray max_angle{"MaxAngle", 1, std::vector<double>(n), true};
  io::DataArray radius_edge{"RadiusEdgeRatio", 1, std::vector<double>(n), true};
  io::DataArray area{"Area", 1, std::vector<double>(n)};
  io::DataArray is_bad{"IsBad", 1, std::vector<double>(n), true};

#pragma omp parallel for schedule(static)
  for (long long t = 0; t < n; ++t) {
    const auto& tri = mesh.triangles[t];
    const Point2& a = mesh.points[tri[0]];
    const Point2& b = mesh.points[tri[1]];
    const Point2& c = mesh.points[tri[2]];
    double lo = 0, hi = 0;
    triangle_angles(a, b, c, lo, hi);
    min_angle.values[t] = lo;
    max_angle.values[t] = hi;
    radius_edge.values[t] = triangle_radius_edge(a, b, c);
    area.values[t] = triangle_area(a, b, c);
    is_bad.values[t] = (min_angle_deg > 0 && lo < min_angle_deg) ? 1.0 : 0.0;
  }

  io::Attributes attributes;
  // Moved one by one: a braced list would copy each array (its elements are const).
  for (io::DataArray* a : {&min_angle, &max_angle, &radius_edge, &area, &is_bad})
    attributes.cell_data.push_back(std::move(*a));
  return attributes;
}

io::Attributes tet_attributes(const QualityTetResult& r) {
  io::Attributes attributes;
  // Written in the precision the mesher measured them in: single, but volumes in double.
  auto add = [&attributes](const char* name, const auto& values, bool float32) {
    attributes.cell_data.push_back(
        {name, 1, std::vector<double>(values.begin(), values.end()), float32});
  };
  add("RadiusEdgeRatio", r.radius_edge, true);
  add("MinDihedralAngle", r.min_dihedral, true);
  add("MaxDihedralAngle", r.max_dihedral, true);
  add("Volume", r.volume, false);
  add("IsBad", r.is_bad, true);
  return attributes;
}

}  // namespace gdr::cli
