// One-paragraph summary of a validation report.
#include <cmath>
#include <cstdio>

#include "gdr/validate.h"

namespace gdr {

std::string ValidationReport::summary() const {
  std::string s = valid ? "Mesh is valid" : "Mesh is INVALID";
  const struct {
    std::size_t count;
    const char* what;
  } counters[] = {{invalid_indices, "elements with bad vertex indices"},
                  {inverted_elements, "inverted elements"},
                  {nonmanifold, "non-manifold edges/faces"},
                  {boundary_errors, "boundary errors"},
                  {invalid_subsegments, "subsegments that are not mesh edges"},
                  {invalid_subfaces, "subfaces that are not mesh faces"},
                  {missing_points, "missing input points"},
                  {missing_segments, "missing input segments"},
                  {missing_facets, "uncovered input facets"},
                  {non_delaunay, "non-Delaunay edges/faces"}};
  std::string errors;
  for (const auto& c : counters)
    if (c.count) errors += (errors.empty() ? "" : ", ") + std::to_string(c.count) + " " + c.what;
  if (!errors.empty()) s += " (" + errors + ")";
  char buf[512];
  const QualityStats& q = quality;
  // Ratios of flat elements and areas beyond the doubles print as numbers, never inf or nan.
  const auto ratio = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, v < 1e6 ? "%.3f" : "%.3g", v);
    return std::string(b);
  };
  const std::string measure =
      std::isfinite(q.total_measure) ? (std::snprintf(buf, sizeof buf, "%.6g", q.total_measure), buf)
                                     : "beyond 1.8e308";
  const bool tets = q.min_dihedral_deg != 0 || q.max_dihedral_deg != 0;
  if (tets) {
    std::snprintf(buf, sizeof buf,
                  ". %zu tetrahedra, volume %s; dihedral angles %.2f..%.2f deg; radius-edge "
                  "mean %s, max %s; %zu bad (%.2f%% of the volume).",
                  q.elements, measure.c_str(), q.min_dihedral_deg, q.max_dihedral_deg,
                  ratio(q.mean_radius_edge).c_str(), ratio(q.max_radius_edge).c_str(),
                  q.bad_elements, q.bad_measure_percent);
  } else {
    std::snprintf(buf, sizeof buf,
                  ". %zu triangles, area %s; angles %.2f..%.2f deg; radius-edge mean %s, "
                  "max %s; %zu bad (%.2f%% of the area).",
                  q.elements, measure.c_str(), q.min_angle_deg, q.max_angle_deg,
                  ratio(q.mean_radius_edge).c_str(), ratio(q.max_radius_edge).c_str(),
                  q.bad_elements, q.bad_measure_percent);
  }
  s += buf;
  if (!problems.empty()) s += " First problem: " + problems.front() + ".";
  return s;
}

}  // namespace gdr
