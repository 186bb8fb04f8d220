#include "instruction_set.hpp"

#include <atomic>
#include <cstdlib>
#include <stdexcept>
#include <string>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define SWARMCOLLIDE_WIDER_SETS 1
#endif

namespace swarmcollide::detail {

namespace {

KernelIsa from_environment() {
  const char* requested = std::getenv("SWARMCOLLIDE_ISA");
  if (requested == nullptr || *requested == '\0') return widest_kernel_isa();
  const std::optional<KernelIsa> isa = kernel_isa_from_name(requested);
  if (!isa || !kernel_isa_available(*isa)) {
    throw std::runtime_error(std::string("SWARMCOLLIDE_ISA=") + requested +
                             " names no instruction set this build and processor run (use "
                             "avx512, avx2 or baseline, or unset it)");
  }
  return *isa;
}

// The set chosen, -1 before the first call; a race only makes two threads choose the same set.
std::atomic<int> chosen{-1};

}  // namespace

const char* kernel_isa_name(KernelIsa isa) {
  switch (isa) {
    case KernelIsa::avx512:
      return "avx512";
    case KernelIsa::avx2:
      return "avx2";
    case KernelIsa::baseline:
      break;
  }
  return "baseline";
}

std::optional<KernelIsa> kernel_isa_from_name(std::string_view name) {
  for (KernelIsa isa : {KernelIsa::baseline, KernelIsa::avx2, KernelIsa::avx512}) {
    if (name == kernel_isa_name(isa)) return isa;
  }
  return std::nullopt;
}

bool kernel_isa_available(KernelIsa isa) {
#ifdef SWARMCOLLIDE_WIDER_SETS
  __builtin_cpu_init();
  if (isa == KernelIsa::avx512) return __builtin_cpu_supports("x86-64-v4");
  if (isa == KernelIsa::avx2) return __builtin_cpu_supports("x86-64-v3");
  return true;
#else
  return isa == KernelIsa::baseline;
#endif
}

KernelIsa widest_kernel_isa() {
  for (KernelIsa isa : {KernelIsa::avx512, KernelIsa::avx2}) {
    if (kernel_isa_available(isa)) return isa;
  }
  return KernelIsa::baseline;
}

KernelIsa kernel_isa() {
  int isa = chosen.load(std::memory_order_acquire);
  if (isa < 0) {
    isa = static_cast<int>(from_environment());
    chosen.store(isa, std::memory_order_release);
  }
  return static_cast<KernelIsa>(isa);
}

void use_kernel_isa(KernelIsa isa) {
  if (!kernel_isa_available(isa)) {
    throw std::invalid_argument(std::string("the ") + kernel_isa_name(isa) +
                                " kernels cannot run here");
  }
  chosen.store(static_cast<int>(isa), std::memory_order_release);
}

}  // namespace swarmcollide::detail
