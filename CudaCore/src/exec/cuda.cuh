// The CUDA execution space: kernels on the current device, stream-ordered allocations
// (cudaMallocAsync pool: cheap enough to allocate per phase), CUB scans.
#pragma once
#include <cuda_runtime.h>

#include <cooperative_groups.h>
#include <cub/block/block_scan.cuh>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_scan.cuh>
#include <algorithm>
#include <cstring>
#include <string>

#include "exec/space.h"
#include "gdr/error.h"

namespace gdr::exec {

namespace detail {
inline void cuda_check(cudaError_t e, const char* what) {
  if (e == cudaSuccess) return;
  cudaGetLastError();  // clear sticky-free errors
  if (e == cudaErrorMemoryAllocation)
    throw Error(Status::OutOfDeviceMemory, std::string("GPU out of memory (") + what + ")");
  throw Error(Status::InternalError,
              std::string("CUDA error in ") + what + ": " + cudaGetErrorString(e));
}

template <class F>
__global__ void for_each_kernel(long long n, F f) {
  long long i = blockIdx.x * (long long)blockDim.x + threadIdx.x;
  if (i < n) f(i);
}
// One chunk of an ExpandList round in a block: thread j steps tuple left + j of the window
// (if j < w) into out[0..n), and the block scan gives its offset among the block's `total`.
template <int K, class BlockScan, class Tuple, class Step>
__device__ __forceinline__ void step_chunk(const Step& step, Tuple* H, long long left, long long j,
                                           long long w, typename BlockScan::TempStorage& storage,
                                           Tuple (&out)[K], int& n, int& offset, int& total) {
  n = j < w ? step(left + j, H[left + j], out) : 0;
  BlockScan(storage).ExclusiveSum(n, offset, total);
}

// ExpandList rounds on small windows, all in one block: a round needs no launch and no
// host round trip (cavities' long tails take hundreds of such rounds). Starts from left,
// right, rounds and writes where it stopped to io = {left, right, rounds}: where the host
// loop would (limits), when the window outgrows one block's share of work, or when H's
// capacity might not hold the next round.
constexpr int kSmallRoundThreads = 1024;

template <int K, class Tuple, class Step>
__global__ void __launch_bounds__(kSmallRoundThreads)
small_rounds_kernel(Tuple* H, long long left, long long right, int rounds, long long* io,
                    long long cap, Step step, int max_rounds, int defer_after_rounds,
                    long long defer_below, long long max_window) {
  using BlockScan = cub::BlockScan<int, kSmallRoundThreads>;
  __shared__ typename BlockScan::TempStorage scan_storage;
  for (;;) {  // every thread holds the same left/right/rounds: the exits are uniform
    const long long w = right - left;
    if (w == 0 || w > max_window || right + w * K > cap || rounds >= max_rounds ||
        (rounds >= defer_after_rounds && w < defer_below))
      break;
    long long added = 0;
    for (long long c = 0; c < w; c += kSmallRoundThreads) {
      Tuple out[K];
      int n, offset, total;
      step_chunk<K, BlockScan>(step, H, left, c + threadIdx.x, w, scan_storage, out, n, offset, total);
      for (int k = 0; k < n; ++k) H[right + added + offset + k] = out[k];
      added += total;
      __syncthreads();  // scan storage reuse; this chunk's writes visible to the block
    }
    left = right;
    right += added;
    ++rounds;
  }
  if (threadIdx.x == 0) {
    io[0] = left;
    io[1] = right;
    io[2] = rounds;
  }
}

// ExpandList rounds on large windows in one cooperative launch over the whole GPU: a round
// costs a grid barrier instead of launches, a scan and a host round trip (the first
// iterations of the 3D meshers grow cavities of hundreds of tetrahedra for over a hundred
// rounds). Each block appends its tuples at an offset taken from a round counter; three
// counters in turn (state[3..5]) let a round's counter be cleared while no block can still
// be reading it. Stops, writing state = {left, right, rounds}, where the host loop would,
// when the window falls to the one-block kernel's size, or when H might not hold a round.
constexpr int kGridRoundThreads = 256;

template <int K, class Tuple, class Step>
__global__ void __launch_bounds__(kGridRoundThreads)
grid_rounds_kernel(Tuple* H, long long* state, long long cap, Step step, int max_rounds,
                   int defer_after_rounds, long long defer_below, long long min_window) {
  using BlockScan = cub::BlockScan<int, kGridRoundThreads>;
  __shared__ typename BlockScan::TempStorage scan_storage;
  __shared__ unsigned long long block_base;
  cooperative_groups::grid_group grid = cooperative_groups::this_grid();
  auto* counter = reinterpret_cast<unsigned long long*>(state + 3);
  long long left = state[0], right = state[1];
  int rounds = static_cast<int>(state[2]);
  for (int q = 0;; ++q) {  // every thread holds the same left/right/rounds: the exits are uniform
    const long long w = right - left;
    if (w <= min_window || right + w * K > cap || rounds >= max_rounds ||
        (rounds >= defer_after_rounds && w < defer_below))
      break;
    if (q >= 1 && grid.thread_rank() == 0) counter[(q + 1) % 3] = 0;  // read before the last barrier
    const long long stride = static_cast<long long>(gridDim.x) * kGridRoundThreads;
    for (long long c = static_cast<long long>(blockIdx.x) * kGridRoundThreads; c < w; c += stride) {
      Tuple out[K];
      int n, offset, total;
      step_chunk<K, BlockScan>(step, H, left, c + threadIdx.x, w, scan_storage, out, n, offset, total);
      if (threadIdx.x == 0) block_base = total ? atomicAdd(&counter[q % 3], static_cast<unsigned long long>(total)) : 0;
      __syncthreads();
      for (int k = 0; k < n; ++k) H[right + static_cast<long long>(block_base) + offset + k] = out[k];
      __syncthreads();  // scan storage and block_base reuse
    }
    grid.sync();
    const long long added = static_cast<long long>(*reinterpret_cast<volatile unsigned long long*>(&counter[q % 3]));
    left = right;
    right += added;
    ++rounds;
  }
  if (grid.thread_rank() == 0) {
    state[0] = left;
    state[1] = right;
    state[2] = rounds;
  }
}

}  // namespace detail

template <>
struct Ops<Cuda> {
  static constexpr bool is_gpu = true;

  static void* allocate(std::size_t bytes) {
    if (bytes == 0) bytes = 1;
    void* p = nullptr;
    cudaError_t e = cudaMallocAsync(&p, bytes, 0);
    if (e != cudaSuccess) {
      // Free cached pool memory once and retry before giving up.
      cudaGetLastError();
      cudaDeviceSynchronize();
      cudaMemPool_t pool;
      if (cudaDeviceGetDefaultMemPool(&pool, 0) == cudaSuccess) cudaMemPoolTrimTo(pool, 0);
      e = cudaMallocAsync(&p, bytes, 0);
      if (e != cudaSuccess) {
        cudaGetLastError();
        throw Error(Status::OutOfDeviceMemory,
                    "GPU out of memory allocating " + std::to_string(bytes >> 20) + " MiB (" +
                        std::to_string(memory_counter<Cuda>().current >> 20) +
                        " MiB already held by the mesher)");
      }
    }
    memory_counter<Cuda>().add(bytes);
    return p;
  }
  static void deallocate(void* p, std::size_t bytes) {
    cudaFreeAsync(p, 0);
    memory_counter<Cuda>().sub(bytes == 0 ? 1 : bytes);
  }
  static void copy_to_space(void* dst, const void* src, std::size_t bytes) {
    detail::cuda_check(cudaMemcpy(dst, src, bytes, cudaMemcpyHostToDevice), "upload");
  }
  // Large downloads go through two pinned staging buffers: the copy of one chunk from the
  // device overlaps the (multi-threaded) copy of the previous one into pageable memory.
  static void copy_to_host(void* dst, const void* src, std::size_t bytes) {
    constexpr std::size_t kChunk = std::size_t(32) << 20;
    static char* staging[2] = {nullptr, nullptr};
    static cudaStream_t stream = nullptr;
    static cudaEvent_t done[2];
    if (bytes < 2 * kChunk || (!staging[0] && !init_staging(staging, &stream, done, kChunk))) {
      detail::cuda_check(cudaMemcpy(dst, src, bytes, cudaMemcpyDeviceToHost), "download");
      return;
    }
    detail::cuda_check(cudaDeviceSynchronize(), "download");
    const std::size_t n = (bytes + kChunk - 1) / kChunk;
    auto issue = [&](std::size_t c) {
      const std::size_t len = std::min(kChunk, bytes - c * kChunk);
      detail::cuda_check(cudaMemcpyAsync(staging[c & 1], static_cast<const char*>(src) + c * kChunk,
                                         len, cudaMemcpyDeviceToHost, stream),
                         "download");
      detail::cuda_check(cudaEventRecord(done[c & 1], stream), "download");
    };
    issue(0);
    for (std::size_t c = 0; c < n; ++c) {
      if (c + 1 < n) issue(c + 1);
      detail::cuda_check(cudaEventSynchronize(done[c & 1]), "download");
      const std::size_t len = std::min(kChunk, bytes - c * kChunk);
      char* out = static_cast<char*>(dst) + c * kChunk;
      const char* in = staging[c & 1];
      const long long parts = 16;
#pragma omp parallel for
      for (long long p = 0; p < parts; ++p) {
        const std::size_t b = len * p / parts, e = len * (p + 1) / parts;
        std::memcpy(out + b, in + b, e - b);
      }
    }
  }
  static bool init_staging(char** staging, cudaStream_t* stream, cudaEvent_t* done,
                           std::size_t chunk) {
    for (int i = 0; i < 2; ++i)
      if (cudaMallocHost(&staging[i], chunk) != cudaSuccess || cudaEventCreate(&done[i]) != cudaSuccess) {
        cudaGetLastError();
        staging[0] = staging[1] = nullptr;
        return false;
      }
    if (cudaStreamCreateWithFlags(stream, cudaStreamNonBlocking) != cudaSuccess) {
      cudaGetLastError();
      staging[0] = staging[1] = nullptr;
      return false;
    }
    return true;
  }
  static void copy_d2d(void* dst, const void* src, std::size_t bytes) {
    detail::cuda_check(cudaMemcpyAsync(dst, src, bytes, cudaMemcpyDeviceToDevice, 0), "copy");
  }
  static void zero(void* p, std::size_t bytes) {
    detail::cuda_check(cudaMemsetAsync(p, 0, bytes, 0), "memset");
  }
  // Returns cached pool memory to the driver (end of a run).
  static void trim() {
    cudaDeviceSynchronize();
    cudaMemPool_t pool;
    if (cudaDeviceGetDefaultMemPool(&pool, 0) == cudaSuccess) cudaMemPoolTrimTo(pool, 0);
    cudaGetLastError();
  }
  static void synchronize() { detail::cuda_check(cudaDeviceSynchronize(), "synchronize"); }

  template <class F>
  static void for_each(std::size_t n, F f) {
    if (n == 0) return;
    const int block = 256;
    const long long grid = (static_cast<long long>(n) + block - 1) / block;
    detail::for_each_kernel<<<static_cast<unsigned>(grid), block>>>(static_cast<long long>(n), f);
    detail::cuda_check(cudaGetLastError(), "kernel launch");
  }

  template <class F>
  static void for_each_heavy(std::size_t n, F f) {  // see Ops<Cpu>::for_each_heavy
    for_each(n, f);
  }

  // See detail::small_rounds_kernel. Updates left, right and rounds.
  template <int K, class Tuple, class Step>
  static void small_rounds(Tuple* H, std::size_t& left, std::size_t& right, std::size_t cap,
                           const Step& step, int& rounds, int max_rounds, int defer_after_rounds,
                           std::size_t defer_below, std::size_t max_window) {
    // The kernel writes {left, right, rounds} into mapped pinned host memory, read after
    // the one synchronisation the host needs anyway.
    struct Mapped {
      long long* host = nullptr;
      long long* device = nullptr;
    };
    static const Mapped m = [] {
      Mapped r;
      detail::cuda_check(cudaHostAlloc(reinterpret_cast<void**>(&r.host), 3 * sizeof(long long),
                                       cudaHostAllocMapped),
                         "small rounds");
      detail::cuda_check(cudaHostGetDevicePointer(reinterpret_cast<void**>(&r.device), r.host, 0),
                         "small rounds");
      return r;
    }();
    long long* io = m.device;
    const long long* back = m.host;
    detail::small_rounds_kernel<K><<<1, detail::kSmallRoundThreads>>>(
        H, static_cast<long long>(left), static_cast<long long>(right), rounds, io,
        static_cast<long long>(cap), step, max_rounds, defer_after_rounds,
        static_cast<long long>(defer_below), static_cast<long long>(max_window));
    detail::cuda_check(cudaGetLastError(), "small rounds launch");
    detail::cuda_check(cudaStreamSynchronize(0), "small rounds");
    left = static_cast<std::size_t>(back[0]);
    right = static_cast<std::size_t>(back[1]);
    rounds = static_cast<int>(back[2]);
  }

  // See detail::grid_rounds_kernel. Updates left, right and rounds; false where the device
  // cannot launch it cooperatively (the caller then runs rounds the normal way).
  template <int K, class Tuple, class Step>
  static bool grid_rounds(Tuple* H, std::size_t& left, std::size_t& right, std::size_t cap,
                          const Step& step, int& rounds, int max_rounds, int defer_after_rounds,
                          std::size_t defer_below, std::size_t min_window) {
    auto kernel = detail::grid_rounds_kernel<K, Tuple, Step>;
    static const int blocks = [&] {
      int device = 0, cooperative = 0, sms = 0, per_sm = 0;
      if (cudaGetDevice(&device) != cudaSuccess ||
          cudaDeviceGetAttribute(&cooperative, cudaDevAttrCooperativeLaunch, device) != cudaSuccess ||
          cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, device) != cudaSuccess ||
          cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, kernel, detail::kGridRoundThreads, 0) !=
              cudaSuccess) {
        cudaGetLastError();
        return 0;
      }
      return cooperative ? sms * per_sm : 0;
    }();
    if (blocks == 0) return false;
    // The state lives on the device (the blocks' atomics on the round counters must not
    // cross the bus); it travels through pinned host memory before and after.
    struct State {
      long long* host = nullptr;
      long long* device = nullptr;
    };
    static const State st = [] {
      State r;
      detail::cuda_check(cudaMallocHost(reinterpret_cast<void**>(&r.host), 6 * sizeof(long long)),
                         "grid rounds");
      detail::cuda_check(cudaMalloc(reinterpret_cast<void**>(&r.device), 6 * sizeof(long long)),
                         "grid rounds");
      return r;
    }();
    long long* state = st.host;
    state[0] = static_cast<long long>(left);
    state[1] = static_cast<long long>(right);
    state[2] = rounds;
    state[3] = state[4] = state[5] = 0;
    detail::cuda_check(cudaMemcpyAsync(st.device, state, 6 * sizeof(long long), cudaMemcpyHostToDevice, 0),
                       "grid rounds");
    long long cap_ll = static_cast<long long>(cap), below = static_cast<long long>(defer_below),
              min_w = static_cast<long long>(min_window);
    long long* dev_state = st.device;
    Step step_copy = step;
    void* args[] = {&H, &dev_state, &cap_ll, &step_copy, &max_rounds, &defer_after_rounds, &below, &min_w};
    detail::cuda_check(cudaLaunchCooperativeKernel(reinterpret_cast<const void*>(kernel), blocks,
                                                   detail::kGridRoundThreads, args, 0, 0),
                       "grid rounds launch");
    detail::cuda_check(cudaMemcpyAsync(state, st.device, 3 * sizeof(long long), cudaMemcpyDeviceToHost, 0),
                       "grid rounds");
    detail::cuda_check(cudaStreamSynchronize(0), "grid rounds");
    left = static_cast<std::size_t>(state[0]);
    right = static_cast<std::size_t>(state[1]);
    rounds = static_cast<int>(state[2]);
    return true;
  }

  // Stable sort of (key, value) pairs by key (radix sort, through scratch copies).
  static void sort_pairs(unsigned long long* keys, int* values, std::size_t n) {
    if (n < 2) return;
    auto* k2 = static_cast<unsigned long long*>(allocate(n * sizeof(unsigned long long)));
    auto* v2 = static_cast<int*>(allocate(n * sizeof(int)));
    std::size_t temp_bytes = 0;
    detail::cuda_check(cub::DeviceRadixSort::SortPairs(nullptr, temp_bytes, keys, k2, values, v2, (int)n),
                       "sort size");
    void* temp = allocate(temp_bytes);
    const cudaError_t e = cub::DeviceRadixSort::SortPairs(temp, temp_bytes, keys, k2, values, v2, (int)n);
    deallocate(temp, temp_bytes);
    if (e == cudaSuccess) {
      copy_d2d(keys, k2, n * sizeof(unsigned long long));
      copy_d2d(values, v2, n * sizeof(int));
    }
    deallocate(k2, n * sizeof(unsigned long long));
    deallocate(v2, n * sizeof(int));
    detail::cuda_check(e, "sort");
  }

  template <class T>
  static T exclusive_scan(const T* in, T* out, std::size_t n) {
    if (n == 0) return T(0);
    // Total = last input + last output. Both are copied into pinned memory in stream order
    // (the first before the scan, as `in` may alias `out`), so one synchronisation reads both.
    static_assert(sizeof(T) <= 8, "scan of 8-byte values at most");
    T* last = pinned_pair<T>();
    detail::cuda_check(cudaMemcpyAsync(&last[0], in + n - 1, sizeof(T), cudaMemcpyDeviceToHost, 0),
                       "scan");
    std::size_t temp_bytes = 0;
    detail::cuda_check(cub::DeviceScan::ExclusiveSum(nullptr, temp_bytes, in, out, (int)n),
                       "scan size");
    void* temp = allocate(temp_bytes);
    cudaError_t e = cub::DeviceScan::ExclusiveSum(temp, temp_bytes, in, out, (int)n);
    deallocate(temp, temp_bytes);
    detail::cuda_check(e, "scan");
    detail::cuda_check(cudaMemcpyAsync(&last[1], out + n - 1, sizeof(T), cudaMemcpyDeviceToHost, 0),
                       "scan");
    detail::cuda_check(cudaStreamSynchronize(0), "scan");
    return last[0] + last[1];
  }

  // Two pinned host slots for scan totals (allocated once per process and type).
  template <class T>
  static T* pinned_pair() {
    static T* p = [] {
      void* q = nullptr;
      detail::cuda_check(cudaMallocHost(&q, 2 * sizeof(T)), "pinned allocation");
      return static_cast<T*>(q);
    }();
    return p;
  }
};

}  // namespace gdr::exec
