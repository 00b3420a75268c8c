// The 2D tests that run once per backend: the GPU instance skips itself, with the reason,
// where there is no usable CUDA device (CI), so the same tests run on the GPU machine.
#pragma once
#include <gtest/gtest.h>

#include "gdr/backend.h"

namespace gdr::test {

class OnBackend : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override {
    if (GetParam() == Backend::Gpu && !gpu_available())
      GTEST_SKIP() << "no usable CUDA device: " << device_info().reason;
  }
};

inline auto both_backends() { return ::testing::Values(Backend::Cpu, Backend::Gpu); }
inline std::string backend_name(const ::testing::TestParamInfo<Backend>& info) {
  return info.param == Backend::Gpu ? "Gpu" : "Cpu";
}

}  // namespace gdr::test
