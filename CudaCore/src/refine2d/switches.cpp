// Triangle's switch string mapped to Refine2dOptions (gdr/refine2d.h).
#include <cctype>
#include <cstdlib>
#include <string>

#include "gdr/refine2d.h"

namespace gdr {
namespace {

[[noreturn]] void refuse(const std::string& switches, const std::string& why) {
  throw Error(Status::InvalidInput, "Triangle switches '" + switches + "': " + why);
}

// What Triangle itself reads as a number after q, a and S: digits and '.', and for a an
// exponent ("a1e-3").
std::size_t number_end(const std::string& s, std::size_t i, bool exponent) {
  while (i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.')) ++i;
  if (exponent && i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < s.size() && (s[j] == '-' || s[j] == '+')) ++j;
    if (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) {
      i = j;
      while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    }
  }
  return i;
}

}  // namespace

TriangleSwitches apply_triangle_switches(const std::string& switches, Refine2dOptions& o) {
  TriangleSwitches t;
  std::size_t i = !switches.empty() && switches[0] == '-' ? 1 : 0;
  if (i == switches.size()) refuse(switches, "no switches");
  bool pslg = false, convex_hull = false, quality = false, area = false;
  bool region_areas = false, region_attributes = false, circles = false;
  while (i < switches.size()) {
    const char c = switches[i++];
    const bool numbered = c == 'q' || c == 'a' || c == 'S';
    const std::size_t end = numbered ? number_end(switches, i, c == 'a') : i;
    const std::string number = switches.substr(i, end - i);
    i = end;
    char* stop = nullptr;
    const double value = number.empty() ? 0.0 : std::strtod(number.c_str(), &stop);
    if (!number.empty() && *stop != '\0')
      refuse(switches, "'" + std::string(1, c) + number + "' is not a number");
    switch (c) {
      case 'p': pslg = true; break;
      case 'c': convex_hull = true; break;
      case 'q':
        quality = true;
        o.min_angle = number.empty() ? 20.0 : value;
        break;
      case 'a':
        area = true;
        if (number.empty()) region_areas = true;
        else o.max_area = value;
        break;
      case 'A': region_attributes = true; break;
      case 'S':
        if (number.empty()) refuse(switches, "'S' needs the number of Steiner points");
        o.max_steiner_points = static_cast<long long>(value);
        break;
      case 'z': t.zero_based = true; break;
      case 'Q': t.quiet = true; break;
      case 'C': t.check = true; break;
      // Triangle's conforming Delaunay switch: subsegments are encroached by their diametral
      // circles, so that no vertex they see lies in them.
      case 'D': circles = true; break;
      default:
        refuse(switches, "'" + std::string(1, c) +
                             "' is not supported (supported: p, c, q[angle], a[area], A, S<n>, D, "
                             "z, Q, C; see README \"Triangle's switches\")");
    }
  }
  // Triangle refines only with q or a, and without c eats the triangles that segments do
  // not enclose.
  if (!quality) o.min_angle = 0;
  o.refine = quality || area;
  o.remove_exterior = pslg && !convex_hull;
  o.region_areas = region_areas;
  o.region_attributes = region_attributes;
  o.mode = circles ? EncroachMode::Ruppert : EncroachMode::Chew;
  return t;
}

}  // namespace gdr
