// The method table and the one options object: names, capabilities, parameters and validation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

#include "paper_cases.hpp"
#include "swarmcollide/queries/methods.hpp"
#include "swarmcollide/queries/query.hpp"

namespace swarmcollide {
namespace {

using testing::paper_a;
using testing::paper_b_separate;

// The message of the std::invalid_argument that `f` throws (empty when it throws none).
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(MethodTable, ListsEveryMethodOnceWithTheDefaultFirst) {
  const auto& table = method_table();
  ASSERT_EQ(table.size(), 7u);
  EXPECT_EQ(table.front().method, QueryOptions{}.method);
  EXPECT_STREQ(table.front().name, "dual");
  std::set<Method> methods;
  std::set<std::string> names;
  for (const MethodInfo& info : table) {
    methods.insert(info.method);
    names.insert(info.name);
    EXPECT_EQ(method_from_name(info.name), info.method);
    EXPECT_STREQ(method_name(info.method), info.name);
    EXPECT_STREQ(method_info(info.method).name, info.name);
    EXPECT_TRUE(info.capabilities & kCollide) << info.name;
  }
  EXPECT_EQ(methods.size(), table.size());
  EXPECT_EQ(names,
            (std::set<std::string>{"dual", "ipso", "pso", "penalty", "exact", "fcl", "libccd"}));
}

TEST(MethodTable, UnknownNamesListTheValidOnes) {
  const std::string message = error_of([] { method_from_name("fcl-indep"); });
  EXPECT_TRUE(contains(message, "unknown method 'fcl-indep'")) << message;
  for (const MethodInfo& info : method_table()) {
    EXPECT_TRUE(contains(message, "'" + std::string(info.name) + "'")) << message;
  }
}

TEST(MethodTable, WhatEachMethodAnswers) {
  const auto answers = [](Method m) { return method_info(m).capabilities; };
  // libccd reads support functions, and fcl hands FCL its own primitives: both answer curved
  // shapes; the paper's methods read the points as the body and do not.
  EXPECT_EQ(answers(Method::libccd), unsigned{kCollide | kSignedDistance | kCurvedShapes});
  for (Method m : {Method::ipso, Method::pso, Method::penalty}) {
    EXPECT_EQ(answers(m), unsigned{kDistance | kCollide}) << method_name(m);
    EXPECT_FALSE(method_info(m).always_certified);
  }
  for (Method m : {Method::dual, Method::exact, Method::fcl}) {
    EXPECT_EQ(answers(m), unsigned{kDistance | kCollide | kSignedDistance | kCurvedShapes})
        << method_name(m);
  }
  for (Method m : {Method::dual, Method::exact, Method::fcl, Method::libccd}) {
    EXPECT_TRUE(method_info(m).always_certified) << method_name(m);
  }
}

TEST(MethodTable, AQueryAMethodCannotAnswerNamesTheMethodsThatCan) {
  QueryOptions options;
  options.method = Method::libccd;
  const std::string no_distance =
      error_of([&] { Query(options).distance(paper_a(), paper_b_separate()); });
  EXPECT_TRUE(contains(no_distance, "method 'libccd'")) << no_distance;
  EXPECT_TRUE(contains(no_distance, "'fcl'")) << no_distance;
  const std::string able = no_distance.substr(no_distance.find("use one of"));
  EXPECT_FALSE(contains(able, "'libccd'")) << no_distance;
  for (Method m : {Method::ipso, Method::pso, Method::penalty}) {
    options.method = m;
    const std::string no_depth =
        error_of([&] { Query(options).signed_distance(paper_a(), paper_b_separate()); });
    EXPECT_TRUE(contains(no_depth, "signed_distance")) << no_depth;
    EXPECT_TRUE(contains(no_depth, "'dual'")) << no_depth;
  }
}

TEST(MethodTable, EveryDefaultLiesInItsRangeAndEveryParameterCanBeSet) {
  for (const MethodInfo& info : method_table()) {
    QueryOptions options;
    options.method = info.method;
    EXPECT_NO_THROW(options.validate()) << info.name;
    for (const ParameterInfo& p : info.parameters) {
      SCOPED_TRACE(std::string(info.name) + "." + p.name);
      const double value = p.get(options);
      EXPECT_GE(value, p.minimum);
      EXPECT_LE(value, p.maximum);
      EXPECT_EQ(p.kind == ParameterInfo::Kind::choice, !p.choices.empty());
      if (p.kind == ParameterInfo::Kind::choice) {
        EXPECT_EQ(p.maximum, static_cast<double>(p.choices.size() - 1));
      }
      // The far end of the range is accepted and read back.
      const double other = p.maximum == value ? p.minimum : p.maximum;
      QueryOptions changed = options;
      set_parameter(changed, p.name, other);
      EXPECT_EQ(p.get(changed), other);
    }
  }
}

TEST(MethodTable, BadParametersAreNamedWithTheirRangeOrTheMethodsParameters) {
  QueryOptions options;
  options.method = Method::ipso;
  const std::string range = error_of([&] { set_parameter(options, "swarm_size", 1); });
  EXPECT_TRUE(contains(range, "swarm_size must be an integer in [2, 100000], got 1")) << range;
  const std::string fraction = error_of([&] { set_parameter(options, "swarm_size", 2.5); });
  EXPECT_TRUE(contains(fraction, "swarm_size must be an integer")) << fraction;
  const std::string nan = error_of([&] { set_parameter(options, "w_min", std::nan("")); });
  EXPECT_TRUE(contains(nan, "w_min must be a number in [0, 10]")) << nan;
  const std::string foreign = error_of([&] { set_parameter(options, "c1", 2); });
  EXPECT_TRUE(contains(foreign, "c1 does not apply to method 'ipso'")) << foreign;
  EXPECT_TRUE(contains(foreign, "its parameters: tolerance, seed, swarm_size")) << foreign;
  options.method = Method::exact;
  const std::string exact = error_of([&] { set_parameter(options, "swarm_size", 10); });
  EXPECT_TRUE(contains(exact, "(its parameters: tolerance, seed, max_iterations)")) << exact;
  options.method = Method::pso;
  EXPECT_EQ(choice_index(options, "constraint_handling", "feasibility"), 0);
  EXPECT_EQ(choice_index(options, "constraint_handling", "projection"), 1);
  const std::string choice =
      error_of([&] { choice_index(options, "constraint_handling", "penalty"); });
  EXPECT_TRUE(contains(choice, "must be one of 'feasibility', 'projection', got 'penalty'"))
      << choice;
}

TEST(QueryOptions, ToleranceIsRelativeAndZeroIsValid) {
  QueryOptions options;
  for (Scalar bad : {-1e-3, 1.5, std::nan(""), std::numeric_limits<Scalar>::infinity()}) {
    options.tolerance = bad;
    EXPECT_TRUE(
        contains(error_of([&] { options.validate(); }), "tolerance must be a number in [0, 1]"))
        << bad;
    EXPECT_THROW(Query{options}, std::invalid_argument);
  }
  options.tolerance = 0;
  EXPECT_NO_THROW(options.validate());
}

TEST(QueryOptions, OnlyTheMethodsOwnParametersAreValidated) {
  QueryOptions options;
  options.swarm.swarm_size = 0;  // the primal swarms' parameter, which "dual" does not read
  options.penalty.growth_factor = 1;
  EXPECT_NO_THROW(options.validate());
  options.method = Method::ipso;
  EXPECT_TRUE(contains(error_of([&] { options.validate(); }), "swarm_size"));
  for (Method m : {Method::ipso, Method::pso, Method::dual}) {
    QueryOptions inverted;
    inverted.method = m;
    inverted.swarm.w_min = inverted.dual.w_min = 0.95;
    EXPECT_TRUE(contains(error_of([&] { inverted.validate(); }), "w_min must not exceed w_max"))
        << method_name(m);
  }
}

}  // namespace
}  // namespace swarmcollide
