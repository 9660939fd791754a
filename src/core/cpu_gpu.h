// GLINT_CPU_GPU marks a function that is compiled for the CPU and, by nvcc, also for the GPU
// (pbrt-v4's PBRT_CPU_GPU): the maths a ray needs is written once and runs on both.
#pragma once

#if defined(__CUDACC__)
#define GLINT_CPU_GPU __host__ __device__
#define GLINT_GPU __device__
#else
#define GLINT_CPU_GPU
#define GLINT_GPU
#endif

// Unrolls the loop that follows, so that small arrays indexed by its counter stay in
// registers on the GPU (an array indexed at run time lives in slow local memory there).
#if defined(__CUDACC__)
#define GLINT_UNROLL _Pragma("unroll")
#elif defined(__GNUC__) && !defined(__clang__)
#define GLINT_UNROLL _Pragma("GCC unroll 8")
#else
#define GLINT_UNROLL
#endif
