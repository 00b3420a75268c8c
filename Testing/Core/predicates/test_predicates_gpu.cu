// The same adversarial cases evaluated in a CUDA kernel must give the exact signs, and the
// symbolic perturbation must agree with the CPU.
#include <cuda_runtime.h>
#include <gtest/gtest.h>

#include "cases.h"
#include "gdr/backend.h"

namespace gdr::test {
namespace {

__global__ void eval_kernel(Pred p, int npts, int dim, long long n, const double* coords,
                            int* sign, int* stage, int* sos) {
  const long long c = blockIdx.x * static_cast<long long>(blockDim.x) + threadIdx.x;
  if (c >= n) return;
  const double* q[5];
  int idx[5];
  for (int i = 0; i < npts; ++i) {
    q[i] = coords + (c * npts + i) * dim;
    idx[i] = static_cast<int>((c * 31 + i * 7) % 100003);
  }
  sign[c] = eval_sign(p, q, &stage[c]);
  sos[c] = has_sos(p) ? eval_sos(p, q, idx) : 0;
}

#define GDR_CUDA_OK(call) ASSERT_EQ((call), cudaSuccess) << cudaGetErrorString(cudaGetLastError())

class PredicatesGpu : public ::testing::TestWithParam<Pred> {};

TEST_P(PredicatesGpu, AdversarialSignsMatchGmpAndCpu) {
  if (!gpu_available()) GTEST_SKIP() << "no usable CUDA device: " << device_info().reason;
  const Pred p = GetParam();
  CaseSet set = adversarial_cases(p, 1000000, 101 + int(p));  // the CPU test's cases
  compute_reference(set);
  const std::size_t n = set.size();
  double* d_coords = nullptr;
  int *d_sign = nullptr, *d_stage = nullptr, *d_sos = nullptr;
  GDR_CUDA_OK(cudaMalloc(&d_coords, set.coords.size() * sizeof(double)));
  GDR_CUDA_OK(cudaMalloc(&d_sign, n * sizeof(int)));
  GDR_CUDA_OK(cudaMalloc(&d_stage, n * sizeof(int)));
  GDR_CUDA_OK(cudaMalloc(&d_sos, n * sizeof(int)));
  GDR_CUDA_OK(cudaMemcpy(d_coords, set.coords.data(), set.coords.size() * sizeof(double),
                         cudaMemcpyHostToDevice));
  const int block = 128;
  eval_kernel<<<unsigned((n + block - 1) / block), block>>>(p, set.npts, set.dim,
                                                            static_cast<long long>(n), d_coords,
                                                            d_sign, d_stage, d_sos);
  GDR_CUDA_OK(cudaGetLastError());
  GDR_CUDA_OK(cudaDeviceSynchronize());
  std::vector<int> sign(n), stage(n), sos(n);
  GDR_CUDA_OK(cudaMemcpy(sign.data(), d_sign, n * sizeof(int), cudaMemcpyDeviceToHost));
  GDR_CUDA_OK(cudaMemcpy(stage.data(), d_stage, n * sizeof(int), cudaMemcpyDeviceToHost));
  GDR_CUDA_OK(cudaMemcpy(sos.data(), d_sos, n * sizeof(int), cudaMemcpyDeviceToHost));
  cudaFree(d_coords);
  cudaFree(d_sign);
  cudaFree(d_stage);
  cudaFree(d_sos);

  std::size_t wrong = 0, wrong_sos = 0, exact = 0;
  for (std::size_t c = 0; c < n; ++c) {
    wrong += sign[c] != set.ref[c];
    exact += stage[c] == 2;
    if (!has_sos(p)) continue;
    const double* q[5];
    int idx[5];
    for (int i = 0; i < set.npts; ++i) {
      q[i] = set.point(c, i);
      idx[i] = static_cast<int>((static_cast<long long>(c) * 31 + i * 7) % 100003);
    }
    wrong_sos += sos[c] != eval_sos(p, q, idx);
  }
  std::printf("[stats] %s GPU adversarial: %zu cases, exact stage %.2f%%\n", pred_name(p), n,
              100.0 * double(exact) / double(n));
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(wrong_sos, 0u);
}

INSTANTIATE_TEST_SUITE_P(All, PredicatesGpu,
                         ::testing::Values(Pred::Orient2d, Pred::Incircle, Pred::Orient3d,
                                           Pred::Insphere, Pred::DiametralCircle,
                                           Pred::DiametralSphere),
                         [](const auto& info) { return std::string(pred_name(info.param)); });

}  // namespace
}  // namespace gdr::test
