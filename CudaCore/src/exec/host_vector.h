// Host arrays that are filled by a download: std::vector with an allocator that leaves new
// elements uninitialised (gdr::DefaultInitAllocator, the one of the output's FilledVectors),
// so that a large result is not first zeroed by one thread (which on fresh pages costs as
// much as the copy) and the copy's threads touch the pages instead.
#pragma once
#include <type_traits>
#include <vector>

#include "gdr/pslg.h"

namespace gdr::exec {

template <class T>
using HostVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace gdr::exec
