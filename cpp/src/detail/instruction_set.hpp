// The instruction sets the library's kernels are compiled for (the swarm's, swarm_kernels.hpp, and
// the support scans', column_scan.hpp), and the one they run; private to the library's sources.
#pragma once

#include <optional>
#include <string_view>

namespace swarmcollide::detail {

/// The instruction sets the kernels are compiled for: the x86-64 baseline (SSE2), AVX2
/// (x86-64-v3) and AVX-512 (x86-64-v4). Every set gives the same bits.
enum class KernelIsa { baseline, avx2, avx512 };

/// "baseline", "avx2" or "avx512".
const char* kernel_isa_name(KernelIsa isa);

/// The set named by `name` (as kernel_isa_name spells it), or nothing.
std::optional<KernelIsa> kernel_isa_from_name(std::string_view name);

/// Whether this build has kernels for `isa` and this processor can run them (only GCC on x86-64
/// builds the wider sets).
bool kernel_isa_available(KernelIsa isa);

/// The widest set available.
KernelIsa widest_kernel_isa();

/// The set the kernels run: SWARMCOLLIDE_ISA's if it is set, else the widest available, chosen at
/// the first call. Throws std::runtime_error when SWARMCOLLIDE_ISA names no available set.
KernelIsa kernel_isa();

/// Makes every later call of kernel_isa() answer `isa` (tests compare the sets in one process).
/// Throws std::invalid_argument when it is not available.
void use_kernel_isa(KernelIsa isa);

}  // namespace swarmcollide::detail
