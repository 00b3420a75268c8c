// Host arrays that are filled by a download: std::vector with an allocator that leaves new
// elements uninitialised, so that a large result is not first zeroed by one thread (which on
// fresh pages costs as much as the copy) and the copy's threads touch the pages instead.
#pragma once
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace gdr::exec {

template <class T>
struct UninitAllocator : std::allocator<T> {
  static_assert(std::is_trivially_copyable_v<T>, "only for plain data");
  template <class U>
  struct rebind {
    using other = UninitAllocator<U>;
  };
  UninitAllocator() = default;
  template <class U>
  UninitAllocator(const UninitAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;  // default-initialisation: no zeroing
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using HostVector = std::vector<T, UninitAllocator<T>>;

}  // namespace gdr::exec
