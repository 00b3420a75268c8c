// The execution-layer tests on the CUDA space; skipped without a usable device.
#include "exec/cuda.cuh"
#include "exec_tests.h"
#include "gdr/backend.h"

#define GDR_NEED_GPU \
  if (!gdr::gpu_available()) GTEST_SKIP() << "no usable CUDA device: " << gdr::device_info().reason

GDR_EXEC_TESTS(ExecCuda, gdr::exec::Cuda, GDR_NEED_GPU)
