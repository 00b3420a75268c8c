// Owning, typed, space-resident array. Kernels never see a Buffer: they take raw pointers
// (or small trivially copyable views built from them) by value.
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

#include "exec/space.h"

namespace gdr::exec {

template <class Space, class T>
class Buffer {
 public:
  Buffer() = default;
  explicit Buffer(std::size_t n) { resize_discard(n); }
  ~Buffer() { release(); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& o) noexcept { swap(o); }
  Buffer& operator=(Buffer&& o) noexcept {
    swap(o);
    return *this;
  }
  void swap(Buffer& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
  }

  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t size() const { return size_; }
  std::size_t capacity() const { return capacity_; }
  bool empty() const { return size_ == 0; }

  // New size; contents are not kept.
  void resize_discard(std::size_t n) {
    if (n > capacity_) {
      release();
      allocate(n);
    }
    size_ = n;
  }
  // New size; the first min(old, n) elements are kept. Grows geometrically, by a sixteenth:
  // mesh arrays grow a little every iteration, device memory per element matters, and the
  // copies are cheap next to the work of an iteration.
  void resize(std::size_t n) {
    if (n > capacity_) {
      std::size_t cap = capacity_ + capacity_ / 16;
      if (cap < n) cap = n;
      Buffer bigger;
      bigger.allocate(cap);
      if (size_) Ops<Space>::copy_d2d(bigger.data_, data_, size_ * sizeof(T));
      swap(bigger);
    }
    size_ = n;
  }
  // Room for n elements without changing the size (contents kept): a loop that grows the
  // array a few elements at a time then copies it once instead of at every sixteenth.
  void reserve(std::size_t n) {
    if (n <= capacity_) return;
    const std::size_t size = size_;
    resize(n);
    size_ = size;
  }
  // Exact-size reallocation (frees slack after compaction).
  void shrink_to(std::size_t n) {
    if (n >= capacity_) return resize(n);
    Buffer smaller;
    smaller.allocate(n);
    if (n) Ops<Space>::copy_d2d(smaller.data_, data_, n * sizeof(T));
    smaller.size_ = n;
    swap(smaller);
  }
  // Scratch that held far more than its last use: freed (contents lost), so that a large
  // early use does not stay allocated while the mesh grows.
  void release_if_oversized() {
    if (capacity_ > 2 * size_ + (std::size_t(1) << 16)) release();
  }
  void release() {
    if (data_) Ops<Space>::deallocate(data_, capacity_ * sizeof(T));
    data_ = nullptr;
    size_ = capacity_ = 0;
  }
  void zero() {
    if (size_) Ops<Space>::zero(data_, size_ * sizeof(T));
  }
  void upload(const T* host, std::size_t n) {
    resize_discard(n);
    if (n) Ops<Space>::copy_to_space(data_, host, n * sizeof(T));
  }
  template <class A>
  void upload(const std::vector<T, A>& host) { upload(host.data(), host.size()); }
  void download(T* host, std::size_t n, std::size_t offset = 0) const {
    if (n) Ops<Space>::copy_to_host(host, data_ + offset, n * sizeof(T));
  }
  std::vector<T> to_host() const {
    std::vector<T> v(size_);
    download(v.data(), size_);
    return v;
  }
  // Into a host vector (a HostVector skips zeroing the new elements).
  template <class Vec>
  void to_host(Vec& v) const {
    v.resize(size_);
    download(v.data(), size_);
  }
  T get(std::size_t i) const {
    T v;
    Ops<Space>::copy_to_host(&v, data_ + i, sizeof(T));
    return v;
  }
  void set(std::size_t i, const T& v) { Ops<Space>::copy_to_space(data_ + i, &v, sizeof(T)); }

 private:
  void allocate(std::size_t n) {
    data_ = static_cast<T*>(Ops<Space>::allocate(n * sizeof(T)));
    capacity_ = n;
  }
  T* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

}  // namespace gdr::exec
