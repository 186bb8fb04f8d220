#pragma once

#include "swarmcollide/types.hpp"

namespace swarmcollide {

/// Inertia weight and acceleration coefficients of one particle.
struct ParticleCoefficients {
  Scalar w;
  Scalar c1;
  Scalar c2;
};

/// (8)-(9): coefficients of the particle ranked `rank` (1 = best personal best) in a swarm of
/// `swarm_size`. Throws std::invalid_argument for a rank outside [1, swarm_size].
ParticleCoefficients rank_adaptive_coefficients(int rank, int swarm_size, Scalar w_min,
                                                Scalar w_max);

/// (7): the inertia weight after `iteration` of `max_iterations` iterations.
Scalar linear_decreasing_inertia(int iteration, int max_iterations, Scalar w_start, Scalar w_end);

/// The instruction set the swarm's vector kernels use in this process: "avx512", "avx2" or
/// "baseline". It is the widest the processor runs unless the environment variable
/// SWARMCOLLIDE_ISA names one of these (read once, at the first solve); every set gives the same
/// answers. Throws std::runtime_error when SWARMCOLLIDE_ISA names a set that cannot run here.
const char* swarm_instruction_set();


}  // namespace swarmcollide
