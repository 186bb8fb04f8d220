// SWARMCOLLIDE_FLATTEN, which inlines everything a function calls into it (GCC's flatten); private
// to the library's sources.
#pragma once

// Not under the sanitizers: GCC 12 took an hour to compile distance_finish.cpp flattened with their
// instrumentation at -O1 (make test-sanitize), against 18 seconds for the release build.
#if defined(__SANITIZE_ADDRESS__)
#define SWARMCOLLIDE_FLATTEN
#else
#define SWARMCOLLIDE_FLATTEN __attribute__((flatten))
#endif
