// The contract suite: every method, every query it answers (from the method table), on the
// paper's pairs, the hard cases and seeded random pairs, against the oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "contract.hpp"
#include "hard_cases.hpp"
#include "oracle.hpp"
#include "paper_cases.hpp"
#include "shapes.hpp"

namespace swarmcollide::testing {
namespace {

enum class CaseSet { paper, hard, random };

const char* set_name(CaseSet set) {
  switch (set) {
    case CaseSet::paper:
      return "paper";
    case CaseSet::hard:
      return "hard";
    case CaseSet::random:
      break;
  }
  return "random";
}

struct Case {
  std::string name;
  ConvexPolyhedron a;
  ConvexPolyhedron b;
};

// Seeded random hulls of 4 to 12 points: well apart, close (0.2 between their boxes), overlapping,
// and flat ones (beside a solid, and coplanar and overlapping).
std::vector<Case> random_cases() {
  Random rng(2026);
  std::vector<Case> cases;
  for (int k = 0; k < 12; ++k) {
    const int na = 4 + (k * 5) % 9;
    const int nb = 4 + (k * 7) % 9;
    Vector3 centre;
    if (k % 3 == 0) {
      centre = 4 * rng.unit();
    } else if (k % 3 == 1) {
      centre = Vector3(2.2, 0.3 * rng.uniform(), 0.3 * rng.uniform());
    } else {
      centre = 0.5 * rng.vector();
    }
    const ConvexPolyhedron a = rng.body(na);
    const ConvexPolyhedron b = rng.body(nb, centre);
    cases.push_back({"random " + std::to_string(k), a, b});
  }
  for (int k = 0; k < 2; ++k) {
    VertexMatrix flat = rng.body(6).vertices();
    flat.col(2).setZero();
    VertexMatrix other = rng.body(6, Vector3(0.5, 0, k == 0 ? 1.5 : 0)).vertices();
    if (k == 1) other.col(2).setZero();
    cases.push_back({k == 0 ? "flat beside a solid" : "coplanar flat bodies overlapping",
                     ConvexPolyhedron(flat), ConvexPolyhedron(other)});
  }
  return cases;
}

// Every case in both orders, so that the contract also checks d(A, B) = d(B, A) (both against
// the oracle); the random pairs are random enough in one order.
std::vector<Case> cases_of(CaseSet set) {
  std::vector<Case> cases;
  const auto both_orders = [&cases](const std::string& name, const ConvexPolyhedron& a,
                                    const ConvexPolyhedron& b) {
    cases.push_back({name, a, b});
    cases.push_back({name + ", swapped", b, a});
  };
  switch (set) {
    case CaseSet::paper:
      both_orders("Section IV-A, touching", paper_a(), paper_b_colliding());
      both_orders("Section IV-B, separate", paper_a(), paper_b_separate());
      break;
    case CaseSet::hard:
      for (const HardCase& c : hard_cases()) both_orders(c.name, c.a, c.b);
      break;
    case CaseSet::random:
      cases = random_cases();
      break;
  }
  return cases;
}

// How close `distance` comes to the true value (the distance, or the signed distance), relative
// to the pair's size, at the default tolerance. The certified methods keep the tolerance. The
// paper's swarms and its penalty baseline reach the paper's Tables 1-2 to about 1e-4; elsewhere
// they promise only their bounds (infinity). At a looser tolerance no method need come closer
// than it.
struct Accuracy {
  Method method;
  Scalar paper;
  Scalar hard;
  Scalar random;
};

constexpr Scalar kBoundsOnly = std::numeric_limits<Scalar>::infinity();
constexpr Accuracy kAccuracy[] = {
    {Method::dual, kDefaultTolerance, kDefaultTolerance, kDefaultTolerance},
    {Method::exact, kDefaultTolerance, kDefaultTolerance, kDefaultTolerance},
    {Method::fcl, kDefaultTolerance, kDefaultTolerance, kDefaultTolerance},
    {Method::libccd, kDefaultTolerance, kDefaultTolerance, kDefaultTolerance},
    {Method::ipso, 1e-4, kBoundsOnly, kBoundsOnly},
    {Method::pso, 1e-4, kBoundsOnly, kBoundsOnly},
    {Method::penalty, 1e-4, kBoundsOnly, kBoundsOnly},
};

Scalar accuracy(Method method, CaseSet set, Scalar tolerance) {
  for (const Accuracy& a : kAccuracy) {
    if (a.method == method) {
      const Scalar reached = set == CaseSet::paper  ? a.paper
                             : set == CaseSet::hard ? a.hard
                                                    : a.random;
      return std::max(reached, tolerance);
    }
  }
  ADD_FAILURE() << "no accuracy for method " << method_name(method);
  return 0;
}

struct ContractCase {
  Method method;
  QueryKind kind;
  CaseSet set;
  Scalar tolerance;
};

// The tolerances the contract runs at: the default, and one loose enough that the methods stop
// early, far from their exact answers (one meaning of tolerance for every method and query).
constexpr Scalar kLooseTolerance = 1e-3;

// Every method with every query its table entry says it answers.
std::vector<ContractCase> contract_cases() {
  std::vector<ContractCase> all;
  for (const MethodInfo& info : method_table()) {
    for (QueryKind kind : {QueryKind::distance, QueryKind::collide, QueryKind::signed_distance}) {
      if (!(info.capabilities & capability_of(kind))) continue;
      for (CaseSet set : {CaseSet::paper, CaseSet::hard, CaseSet::random}) {
        for (Scalar tolerance : {kDefaultTolerance, kLooseTolerance}) {
          all.push_back({info.method, kind, set, tolerance});
        }
      }
    }
  }
  return all;
}

void PrintTo(const ContractCase& c, std::ostream* out) {
  *out << method_name(c.method) << " " << kind_name(c.kind) << " on " << set_name(c.set)
       << " at tolerance " << c.tolerance;
}

class Contract : public ::testing::TestWithParam<ContractCase> {};

TEST_P(Contract, HoldsOnEveryCase) {
  const ContractCase& p = GetParam();
  QueryOptions options;
  options.method = p.method;
  options.tolerance = p.tolerance;
  const Query query(options);
  const Scalar relative_accuracy = accuracy(p.method, p.set, p.tolerance);
  for (const Case& c : cases_of(p.set)) {
    SCOPED_TRACE(c.name);
    const Reference truth = reference(c.a, c.b);
    const PairScale s = scale_of(c.a, c.b, options.tolerance);
    const DistanceResult r = ask(query, p.kind, c.a, c.b);
    expect_contract(c.a, c.b, p.kind, p.method, r, truth, s);
    const Scalar value =
        p.kind == QueryKind::signed_distance ? truth.signed_distance : truth.distance;
    if (p.kind == QueryKind::collide) {
      EXPECT_EQ(query.collide(c.a, c.b), r.colliding);
      // Every unproven verdict goes to "exact", so a verdict is always certified (and then, by
      // the contract, right); a proven one stands.
      EXPECT_TRUE(r.certified);
      const DistanceResult own = query.collision(c.a, c.b, /*escalate=*/false);
      if (own.certified) {
        expect_identical(r, own);
      } else {
        EXPECT_EQ(r.method, Method::exact);
        EXPECT_EQ(r.escalated_from, p.method);
      }
    } else if (relative_accuracy != kBoundsOnly) {
      EXPECT_NEAR(r.distance, value, relative_accuracy * s.size + s.rounding);
    }
    expect_identical(r, ask(query, p.kind, c.a, c.b));
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, Contract, ::testing::ValuesIn(contract_cases()),
                         [](const ::testing::TestParamInfo<ContractCase>& info) {
                           return std::string(method_name(info.param.method)) + "_" +
                                  kind_name(info.param.kind) + "_" + set_name(info.param.set) +
                                  (info.param.tolerance == kLooseTolerance ? "_loose" : "");
                         });

}  // namespace
}  // namespace swarmcollide::testing
