// The plain C++ loop that sc.distance_many is measured against: the same bodies, the same
// queries, one thread, no Python. Reads float64 bodies written by bench/batch.py.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace {

std::vector<double> read_points(const std::string& path, long count, long vertices) {
  std::vector<double> buffer(static_cast<std::size_t>(count * vertices * 3));
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(buffer.data()),
          static_cast<std::streamsize>(buffer.size() * sizeof(double)));
  if (!in) {
    std::fprintf(stderr, "cannot read %ld bodies of %ld points from %s\n", count, vertices,
                 path.c_str());
    std::exit(2);
  }
  return buffer;
}

std::vector<swarmcollide::ConvexPolyhedron> make_bodies(const std::vector<double>& buffer,
                                                        long count, long vertices) {
  std::vector<swarmcollide::ConvexPolyhedron> bodies;
  bodies.reserve(static_cast<std::size_t>(count));
  for (long i = 0; i < count; ++i) {
    bodies.emplace_back(Eigen::Map<const swarmcollide::VertexMatrix>(
        buffer.data() + i * vertices * 3, vertices, 3));
  }
  return bodies;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: %s A.bin B.bin PAIRS VERTICES METHOD REPEATS\n", argv[0]);
    return 2;
  }
  const long pairs = std::atol(argv[3]);
  const long vertices = std::atol(argv[4]);
  swarmcollide::QueryOptions options;
  options.method = swarmcollide::method_from_name(argv[5]);
  // Built once, as a user's loop keeps its Query (sc.distance_many validates its options once).
  const swarmcollide::Query query(options);
  const int repeats = std::atoi(argv[6]);
  const auto points_a = read_points(argv[1], pairs, vertices);
  const auto points_b = read_points(argv[2], pairs, vertices);
  std::vector<double> seconds;
  double checksum = 0;
  for (int r = 0; r < repeats; ++r) {
    // Bodies are built from the arrays each time and released before the clock stops, as
    // distance_many builds them from the arrays it is given and releases them before returning.
    const auto start = std::chrono::steady_clock::now();
    {
      const auto as = make_bodies(points_a, pairs, vertices);
      const auto bs = make_bodies(points_b, pairs, vertices);
      for (long i = 0; i < pairs; ++i) checksum += query.distance(as[i], bs[i]).distance;
    }
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("{\"seconds\": %.6f, \"pairs\": %ld, \"checksum\": %.17g}\n",
              seconds[seconds.size() / 2], pairs, checksum / repeats);
  return 0;
}
