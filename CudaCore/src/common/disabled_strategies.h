// GDR_DISABLE: the design strategies a benchmark switches off (comma-separated names; see
// Benchmarks/README.md). Each mesher maps the names to its own switches.
#pragma once
#include <cstdlib>
#include <sstream>
#include <string>

#include "gdr/error.h"

namespace gdr {

// Calls apply(name) for each name in GDR_DISABLE; apply returns false for a name it does not
// know, which is refused with the `known` names listed.
template <class Apply>
void for_each_disabled_strategy(Apply apply, const char* known) {
  const char* env = std::getenv("GDR_DISABLE");
  if (!env) return;
  std::stringstream list(env);
  std::string name;
  while (std::getline(list, name, ','))
    if (!name.empty() && !apply(name))
      throw Error(Status::InvalidInput,
                  "GDR_DISABLE: unknown strategy '" + name + "' (known: " + known + ")");
}

}  // namespace gdr
