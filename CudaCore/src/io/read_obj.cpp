// Wavefront OBJ surfaces: "v x y z [w]" and "f" lines with corners "v", "v/vt", "v//vn" or
// "v/vt/vn", 1-based or negative (relative to the vertices read so far); polygons become
// one facet each. Other statements (vt, vn, g, o, s, usemtl, mtllib, l, ...) are skipped.
#include <cmath>

#include "gdr/error.h"
#include "gdr/io.h"
#include "io/face_collector.h"
#include "io/text_file.h"

namespace gdr::io {

Surface read_obj(const std::string& path) {
  TextFile file(path);
  Surface surface;
  std::vector<int> corner, first = {0}, face_line;
  Tokens t;
  while (file.next(t)) {
    if (t[0] == "v") {
      if (t.size() < 4) file.fail("expected 'v x y z'");
      const std::string what = "vertex " + std::to_string(surface.points.size() + 1);
      surface.points.push_back({file.real(t[1], "x of " + what), file.real(t[2], "y of " + what),
                                file.real(t[3], "z of " + what)});
    } else if (t[0] == "f") {
      const std::string what = "face " + std::to_string(face_line.size());
      if (t.size() < 4) file.fail(what + " has fewer than 3 corners");
      const long long known = static_cast<long long>(surface.points.size());
      for (std::size_t k = 1; k < t.size(); ++k) {
        // The vertex index is what comes before the first '/'.
        std::string_view token = t[k];
        token = token.substr(0, token.find('/'));
        const long long v = file.integer(token, "a corner of " + what);
        const long long index = v > 0 ? v - 1 : known + v;  // -1 is the last vertex read
        if (v == 0 || index < 0 || (v < 0 && index >= known))
          file.fail(what + " refers to vertex " + std::to_string(v) + ", with " + std::to_string(known) +
                    " vertices read so far");
        if (index > 2147483647LL) file.fail(what + " refers to vertex " + std::to_string(v));
        corner.push_back(static_cast<int>(index));
      }
      first.push_back(static_cast<int>(corner.size()));
      face_line.push_back(file.line());
    }
  }
  // Positive indices may name vertices read after the face: check them now.
  const long long n = static_cast<long long>(surface.points.size());
  FaceCollector faces(surface);
  std::vector<int> c;
  for (std::size_t f = 0; f + 1 < first.size(); ++f) {
    const std::string where = path + ":" + std::to_string(face_line[f]) + ": face " + std::to_string(f);
    c.assign(corner.begin() + first[f], corner.begin() + first[f + 1]);
    for (int v : c)
      if (v >= n)
        throw Error(Status::IoError, where + " refers to vertex " + std::to_string(v + 1) + ", but the file has " +
                                         std::to_string(n));
    if (!faces.add(c, static_cast<int>(f)))
      throw Error(Status::IoError, where + " cannot be triangulated (degenerate or not a simple planar polygon)");
  }
  faces.finish();
  if (surface.triangles.empty()) file.fail("no faces ('f' lines) in the file");
  return surface;
}

}  // namespace gdr::io
