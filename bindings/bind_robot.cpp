#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "conversions.hpp"
#include "swarmcollide/queries/query.hpp"
#include "swarmcollide/robot/kinematics.hpp"
#include "swarmcollide/robot/pair_filter.hpp"
#include "swarmcollide/robot/robot_checker.hpp"
#include "swarmcollide/robot/robot_model.hpp"
#include "swarmcollide/robot/robot_motion.hpp"
#include "swarmcollide/robot/robot_queries.hpp"

namespace swarmcollide::bindings {

namespace {

using PairTable = Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>;

LimitMode limit_mode(const py::handle& value) {
  const std::string name = to_name(value, "limits");
  if (name == "raise") return LimitMode::raise;
  if (name == "clamp") return LimitMode::clamp;
  if (name == "wrap") return LimitMode::wrap;
  throw py::value_error("limits must be 'raise', 'clamp' or 'wrap', got '" + name + "'");
}

JointType joint_type(const std::string& name, const std::string& joint) {
  if (name == "revolute") return JointType::revolute;
  if (name == "continuous") return JointType::continuous;
  if (name == "prismatic") return JointType::prismatic;
  if (name == "fixed") return JointType::fixed;
  throw py::value_error("joint '" + joint + "': type '" + name +
                        "' is not supported; use 'revolute', 'continuous', 'prismatic' or 'fixed'");
}

std::vector<std::string> status_names(const std::vector<MotionStatus>& statuses) {
  std::vector<std::string> names;
  names.reserve(statuses.size());
  for (MotionStatus status : statuses) names.emplace_back(status_name(status));
  return names;
}

std::string joint_type_name(JointType type) {
  static const char* names[] = {"revolute", "continuous", "prismatic", "fixed"};
  return names[static_cast<int>(type)];
}

// A robot model from its tables as Python gives them (RobotModel's constructor arguments).
std::shared_ptr<RobotModel> make_model(const std::vector<std::string>& link_names,
                                       std::vector<Joint> joints,
                                       const std::vector<py::tuple>& geometry_rows) {
  std::vector<Link> links;
  for (const std::string& name : link_names) links.push_back({name});
  std::vector<Geometry> geometries;
  for (const py::tuple& row : geometry_rows) {
    if (row.size() != 4) {
      throw py::value_error("each geometry must be (name, link, origin, body)");
    }
    const auto name = to_name(row[0], "a geometry's name");
    const Pose origin = to_pose(row[2], ("geometry '" + name + "' origin").c_str());
    const int link =
        to_count(row[1], ("geometry '" + name + "' link (-1: the world)").c_str(), -1);
    if (is_compound(row[3])) {
      const auto& parts = row[3].cast<const CompoundBody&>();
      geometries.push_back(Geometry{name, link, origin, parts.envelope(), parts});
    } else {
      geometries.push_back(Geometry{name, link, origin,
                                    BodyArgument(row[3], ("geometry '" + name + "'").c_str()).get(),
                                    std::nullopt});
    }
  }
  return std::make_shared<RobotModel>(std::move(links), std::move(joints), std::move(geometries));
}

py::tuple model_state(const RobotModel& model) {
  std::vector<std::string> links;
  for (const Link& link : model.links()) links.push_back(link.name);
  py::list geometries;
  for (const Geometry& g : model.geometries()) {
    geometries.append(py::make_tuple(g.name, g.link, homogeneous(g.origin),
                                     g.parts ? py::cast(*g.parts) : typed_body(g.body)));
  }
  return py::make_tuple(kStateVersion, links, model.joints(), geometries);
}

std::shared_ptr<RobotModel> model_from_state(const py::object& state) {
  PickledState items(state, "RobotModel", 3);
  const auto links = items.next<std::vector<std::string>>("links");
  auto joints = items.next<std::vector<Joint>>("joints");
  const auto geometries = items.next<std::vector<py::tuple>>("geometries");
  return items.build([&] { return make_model(links, std::move(joints), geometries); });
}

py::tuple joint_state(const Joint& j) {
  return py::make_tuple(kStateVersion, j.name, joint_type_name(j.type), j.parent, j.child,
                        homogeneous(j.origin), j.axis, j.lower, j.upper, j.reference, j.mimic,
                        j.multiplier, j.offset);
}

Joint joint_from_state(const py::object& state) {
  PickledState items(state, "Joint", 12);
  Joint j;
  j.name = items.next("name", [](const py::handle& item) { return to_name(item, "name"); });
  j.type = items.next("type", [&j](const py::handle& item) {
    return joint_type(to_name(item, "type"), j.name);
  });
  const auto index = [](const char* name, int least) {
    return [name, least](const py::handle& item) { return to_count(item, name, least); };
  };
  j.parent = items.next("parent", index("parent", 0));
  j.child = items.next("child", index("child", 0));
  j.origin = items.next("origin", [](const py::handle& item) { return to_pose(item, "origin"); });
  j.axis = items.next("axis", [](const py::handle& item) { return finite_vector3(item, "axis"); });
  j.lower = items.next<Scalar>("lower");
  j.upper = items.next<Scalar>("upper");
  j.reference = items.next<Scalar>("reference");
  j.mimic = items.next("mimic", index("mimic (-1: none)", -1));
  j.multiplier = items.next<Scalar>("multiplier");
  j.offset = items.next<Scalar>("offset");
  return j;
}

// What is inconsistent in robot results rebuilt from their states: columns of other lengths
// (the `row` of a RobotCheck or a RobotMotionCheck reads every column at one index).
std::string distances_error(const RobotDistances& r) {
  std::string wrong = unequal_lengths({{"distance", r.distance.rows()},
                                       {"lower_bound", r.lower_bound.rows()},
                                       {"colliding", r.colliding.rows()},
                                       {"certified", r.certified.rows()}});
  if (wrong.empty()) {
    wrong = unequal_lengths({{"distance columns", r.distance.cols()},
                             {"lower_bound columns", r.lower_bound.cols()},
                             {"colliding columns", r.colliding.cols()},
                             {"certified columns", r.certified.cols()}});
  }
  return wrong;
}

std::string check_error(const RobotCheck& r) {
  std::string wrong = unequal_lengths(
      {{"colliding", r.colliding.rows()}, {"min_distance", r.min_distance.rows()},
       {"lower_bound", r.lower_bound.rows()}, {"certified", r.certified.rows()},
       {"pair", r.pair.rows()}, {"point_a", r.point_a.rows()}, {"point_b", r.point_b.rows()},
       {"normal", r.normal.rows()}});
  // No gradient is one of no rows.
  if (wrong.empty() && r.gradient.rows() != 0) {
    wrong = unequal_lengths({{"colliding", r.colliding.rows()}, {"gradient", r.gradient.rows()}});
  }
  return wrong;
}

py::tuple motion_check_state(const RobotMotionCheck& r) {
  return py::make_tuple(kStateVersion, r.touches, r.t_lower, r.t_upper, r.configuration, r.pair,
                        r.distance, r.point_a, r.point_b, r.normal, r.certified, r.iterations,
                        status_names(r.status));
}

RobotMotionCheck motion_check_from_state(const py::object& state) {
  PickledState items(state, "RobotMotionCheck", 12);
  RobotMotionCheck r;
  r.touches = items.next<Eigen::Array<bool, Eigen::Dynamic, 1>>("touches");
  r.t_lower = items.next<VectorX>("t_lower");
  r.t_upper = items.next<VectorX>("t_upper");
  r.configuration = items.next<Configurations>("configuration");
  r.pair = items.next<Eigen::VectorXi>("pair");
  r.distance = items.next<VectorX>("distance");
  r.point_a = items.next<VertexMatrix>("point_a");
  r.point_b = items.next<VertexMatrix>("point_b");
  r.normal = items.next<VertexMatrix>("normal");
  r.certified = items.next<Eigen::Array<bool, Eigen::Dynamic, 1>>("certified");
  r.iterations = items.next<Eigen::VectorXi>("iterations");
  r.status = items.next("status", [](const py::handle& item) {
    std::vector<MotionStatus> statuses;
    for (const py::handle name : py::iter(item)) statuses.push_back(motion_status(name, "status"));
    return statuses;
  });
  const std::string wrong = unequal_lengths(
      {{"touches", r.touches.rows()}, {"t_lower", r.t_lower.rows()},
       {"t_upper", r.t_upper.rows()}, {"configuration", r.configuration.rows()},
       {"pair", r.pair.rows()}, {"distance", r.distance.rows()}, {"point_a", r.point_a.rows()},
       {"point_b", r.point_b.rows()}, {"normal", r.normal.rows()},
       {"certified", r.certified.rows()}, {"iterations", r.iterations.rows()},
       {"status", static_cast<Eigen::Index>(r.status.size())}});
  if (!wrong.empty()) throw items.error(wrong);
  return r;
}

// Geometry pairs, an (n, 2) array-like of integer indices (none when empty). pybind11's own
// conversion to an int matrix would read a pair of floats (0.9, 2.5) as (0, 2) without a word.
std::vector<GeometryPair> to_pairs(const Given<PairTable>& given) {
  // NumPy's own conversion, without the import lookup of numpy.asarray (a planner's check of one
  // state passes its table on every call).
  const py::array array = py::array::ensure(given.value);
  if (!array) {
    throw py::type_error("pairs must be an (n, 2) array of integer geometry indices, got " +
                         type_name(given.value));
  }
  if (array.size() == 0) return {};
  if (array.dtype().kind() != 'i' && array.dtype().kind() != 'u') {
    throw py::type_error("pairs must be an (n, 2) array of integer geometry indices, got " +
                         std::string(py::str(array.dtype())) + " values");
  }
  if (array.ndim() != 2 || array.shape(1) != 2) {
    throw py::value_error("pairs must be an (n, 2) array of integer geometry indices, got shape " +
                          std::string(py::str(array.attr("shape"))));
  }
  const auto table =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
  std::vector<GeometryPair> pairs(static_cast<std::size_t>(table.shape(0)));
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const std::int64_t a = table.at(p, 0);
    const std::int64_t b = table.at(p, 1);
    // Refused before they are narrowed to int; the model checks the others against its count.
    if (std::min(a, b) < 0 || std::max(a, b) > std::numeric_limits<int>::max()) {
      throw py::value_error("pairs[" + std::to_string(p) + "] = (" + std::to_string(a) + ", " +
                            std::to_string(b) + ") must name two geometries by index, from 0");
    }
    pairs[p] = {static_cast<int>(a), static_cast<int>(b)};
  }
  return pairs;
}

PairTable to_table(const std::vector<GeometryPair>& pairs) {
  PairTable table(static_cast<Eigen::Index>(pairs.size()), 2);
  for (std::size_t p = 0; p < pairs.size(); ++p) table.row(p) << pairs[p].a, pairs[p].b;
  return table;
}

BatchSettings settings_of(const py::object& threads) {
  BatchSettings settings;
  if (!threads.is_none()) settings.threads = thread_count(threads);
  return settings;
}


// An IndexError unless row i is one of `rows`. A single configuration's (or motion's) answer is
// read by row, as Python values and small arrays: cheaper than reading every field's array to
// index it.
void check_row(Eigen::Index i, Eigen::Index rows) {
  if (i < 0 || i >= rows) {
    throw py::index_error("row " + std::to_string(i) + " is not in [0, " + std::to_string(rows) +
                          ")");
  }
}

// `count` values from `first`, copied into a new array.
py::array_t<Scalar> values(const Scalar* first, py::ssize_t count) {
  return py::array_t<Scalar>(count, first);
}

// Configuration i's answer as RobotCheck.row gives it (the tuple's type deduced: the stubs name each
// element's).
auto check_row_values(const RobotCheck& check, Eigen::Index i) {
  check_row(i, check.colliding.size());
  const py::object gradient =
      check.gradient.rows() > i
          ? py::object(values(check.gradient.row(i).data(), check.gradient.cols()))
          : py::none();
  return py::make_tuple(bool(check.colliding(i)), check.min_distance(i), check.lower_bound(i),
                        bool(check.certified(i)), check.pair(i),
                        values(check.point_a.row(i).data(), 3),
                        values(check.point_b.row(i).data(), 3),
                        values(check.normal.row(i).data(), 3), gradient);
}

// A checker's answer as RobotCheck.row gives a row.
auto checker_row_values(const RobotCheckRow& row) {
  const py::object gradient = row.gradient.size() > 0
                                  ? py::object(values(row.gradient.data(), row.gradient.size()))
                                  : py::none();
  return py::make_tuple(row.colliding, row.min_distance, row.lower_bound, row.certified, row.pair,
                        values(row.point_a.data(), 3), values(row.point_b.data(), 3),
                        values(row.normal.data(), 3), gradient);
}

using ConfigurationRef = Eigen::Ref<const Eigen::Matrix<Scalar, 1, Eigen::Dynamic>>;

// A RobotChecker that Python threads may share: its buffers serve one check at a time, and a
// check that finds them busy (another thread's, the GIL being released while it runs) uses a copy
// of its own rather than wait.
struct SharedChecker {
  RobotChecker checker;
  std::mutex busy;
};

// One configuration admitted and checked without the GIL: the answer, copied out of the buffers.
RobotCheckRow checked(SharedChecker& shared, const ConfigurationRef& q, const py::object& limits) {
  const LimitMode mode = limit_mode(limits);
  py::gil_scoped_release release;
  std::unique_lock<std::mutex> lock(shared.busy, std::try_to_lock);
  if (lock.owns_lock()) return shared.checker.admit_and_check(q.data(), q.size(), mode);
  RobotChecker spare(shared.checker);
  return spare.admit_and_check(q.data(), q.size(), mode);
}

}  // namespace

void bind_robot(py::module_& m) {
  py::class_<Joint>(m, "Joint", R"doc(
A joint of a RobotModel: the child link's frame is ``parent * origin * motion(q - reference)``.

Parameters
----------
name : str
type : str
    'revolute', 'continuous', 'prismatic' or 'fixed'.
parent, child : int
    Link indices.
origin : pose
    The joint frame in the parent link's frame (a (4, 4) rigid transform).
axis : (3,) array
    In the joint frame; normalised by the model.
lower, upper : float
    Limits (ignored for continuous and fixed joints).
reference : float
    The value at which the child sits at ``origin`` (MJCF's ``ref``).
mimic : int
    The index of the joint this one mimics (-1: none); its value is then ``multiplier *
    value(mimicked) + offset`` and it is no degree of freedom.
multiplier, offset : float
)doc")
      .def(py::init([](const Given<std::string>& name, const Given<std::string>& type,
                       const Given<int>& parent, const Given<int>& child,
                       const py::object& origin, const py::object& axis,
                       const Given<Scalar>& lower, const Given<Scalar>& upper,
                       const Given<Scalar>& reference, const Given<int>& mimic,
                       const Given<Scalar>& multiplier, const Given<Scalar>& offset) {
             Joint joint;
             joint.name = to_name(name.value, "name");
             const std::string label = "joint '" + joint.name + "' ";
             const auto named = [&label](const char* argument) { return label + argument; };
             joint.type = joint_type(to_name(type.value, named("type").c_str()), joint.name);
             joint.parent = to_count(parent.value, named("parent").c_str(), 0);
             joint.child = to_count(child.value, named("child").c_str(), 0);
             joint.origin = to_pose(origin, named("origin").c_str());
             joint.axis = finite_vector3(axis, named("axis").c_str());
             joint.lower = to_real(lower.value, named("lower").c_str());
             joint.upper = to_real(upper.value, named("upper").c_str());
             joint.reference = to_real(reference.value, named("reference").c_str());
             // -1 alone stands for none: another negative index is a mistake, not "none".
             joint.mimic = to_count(mimic.value, named("mimic (-1: none)").c_str(), -1);
             joint.multiplier = to_real(multiplier.value, named("multiplier").c_str());
             joint.offset = to_real(offset.value, named("offset").c_str());
             return joint;
           }),
           py::arg("name"), py::arg("type"), py::arg("parent"), py::arg("child"),
           py::arg("origin") = py::none(), py::arg("axis") = Vector3::UnitZ(),
           py::arg("lower") = 0.0, py::arg("upper") = 0.0, py::arg("reference") = 0.0,
           py::arg("mimic") = -1, py::arg("multiplier") = 1.0, py::arg("offset") = 0.0)
      .def_readonly("name", &Joint::name)
      .def_property_readonly("type", [](const Joint& joint) { return joint_type_name(joint.type); })
      .def_readonly("parent", &Joint::parent)
      .def_readonly("child", &Joint::child)
      .def_readonly("axis", &Joint::axis)
      .def_readonly("lower", &Joint::lower)
      .def_readonly("upper", &Joint::upper)
      .def_readonly("reference", &Joint::reference)
      .def_readonly("mimic", &Joint::mimic)
      .def_readonly("multiplier", &Joint::multiplier)
      .def_readonly("offset", &Joint::offset)
      .def(py::pickle(&joint_state, &joint_from_state));

  py::class_<RobotDistances>(m, "RobotDistances",
                             "Signed distances of every checked pair, (m, pairs) each.")
      .def_readonly("distance", &RobotDistances::distance)
      .def_readonly("lower_bound", &RobotDistances::lower_bound)
      .def_readonly("colliding", &RobotDistances::colliding)
      .def_readonly("certified", &RobotDistances::certified)
      .def(pickle_fields<RobotDistances>(
          "RobotDistances", &distances_error, field("distance", &RobotDistances::distance),
          field("lower_bound", &RobotDistances::lower_bound),
          field("colliding", &RobotDistances::colliding),
          field("certified", &RobotDistances::certified)));

  py::class_<RobotCheck>(m, "RobotCheck", "Per configuration: the verdict and the nearest pair.")
      .def_readonly("colliding", &RobotCheck::colliding)
      .def_readonly("min_distance", &RobotCheck::min_distance)
      .def_readonly("lower_bound", &RobotCheck::lower_bound)
      .def_readonly("certified", &RobotCheck::certified)
      .def_readonly("pair", &RobotCheck::pair)
      .def_readonly("point_a", &RobotCheck::point_a)
      .def_readonly("point_b", &RobotCheck::point_b)
      .def_readonly("normal", &RobotCheck::normal)
      .def_readonly("gradient", &RobotCheck::gradient)
      .def(pickle_fields<RobotCheck>(
          "RobotCheck", &check_error, field("colliding", &RobotCheck::colliding),
          field("min_distance", &RobotCheck::min_distance),
          field("lower_bound", &RobotCheck::lower_bound),
          field("certified", &RobotCheck::certified), field("pair", &RobotCheck::pair),
          field("point_a", &RobotCheck::point_a), field("point_b", &RobotCheck::point_b),
          field("normal", &RobotCheck::normal), field("gradient", &RobotCheck::gradient)))
      .def(
          "row",
          &check_row_values,
          py::arg("i"),
          "Configuration i's (colliding, min_distance, lower_bound, certified, pair, point_a, "
          "point_b, normal, gradient or None), as Python values and (3,) or (dof,) arrays: "
          "cheaper than reading every field's array to index it, for a check of one "
          "configuration.");

  py::class_<RobotMotionCheck>(m, "RobotMotionCheck",
                               "Per motion: free, or the first contact bracketed (see "
                               "Robot.check_motion).")
      .def_readonly("touches", &RobotMotionCheck::touches)
      .def_readonly("t_lower", &RobotMotionCheck::t_lower)
      .def_readonly("t_upper", &RobotMotionCheck::t_upper)
      .def_readonly("configuration", &RobotMotionCheck::configuration)
      .def_readonly("pair", &RobotMotionCheck::pair)
      .def_readonly("distance", &RobotMotionCheck::distance)
      .def_readonly("point_a", &RobotMotionCheck::point_a)
      .def_readonly("point_b", &RobotMotionCheck::point_b)
      .def_readonly("normal", &RobotMotionCheck::normal)
      .def_readonly("certified", &RobotMotionCheck::certified)
      .def_readonly("iterations", &RobotMotionCheck::iterations)
      .def(py::pickle(&motion_check_state, &motion_check_from_state))
      .def_property_readonly(
          "status", [](const RobotMotionCheck& check) { return status_names(check.status); },
          "Per motion: 'converged', 'max_iterations' or 'unresolved'.")
      .def(
          "row",
          [](const RobotMotionCheck& check, Eigen::Index i) {
            check_row(i, check.touches.size());
            return py::make_tuple(
                bool(check.touches(i)), check.t_lower(i), check.t_upper(i),
                values(check.configuration.row(i).data(), check.configuration.cols()),
                check.pair(i), check.distance(i), values(check.point_a.row(i).data(), 3),
                values(check.point_b.row(i).data(), 3), values(check.normal.row(i).data(), 3),
                bool(check.certified(i)), check.iterations(i),
                status_name(check.status[static_cast<std::size_t>(i)]));
          },
          py::arg("i"),
          "Motion i's (touches, t_lower, t_upper, configuration, pair, distance, point_a, "
          "point_b, normal, certified, iterations, status), as Python values and arrays.");

  py::class_<RobotModel, std::shared_ptr<RobotModel>>(m, "RobotModel", R"doc(
A robot as a plain table of links, joints and geometries: immutable, shared by every thread.

Parameters
----------
links : list of str
    The link names; joints and geometries refer to links by index.
joints : list of Joint
    Every link but one (the root) is the child of exactly one joint. The moving joints are the
    degrees of freedom, in the order given.
geometries : list of (name, link, origin, body)
    A ConvexPolyhedron or CompoundBody fixed to link ``link`` at ``origin`` (a rigid transform),
    or to the world for ``link == -1`` (an obstacle).

Raises
------
ValueError
    Naming the joint, link or geometry at fault.
)doc")
      .def(py::init(&make_model),
           py::arg("links"), py::arg("joints"), py::arg("geometries"))
      .def(py::pickle(&model_state, &model_from_state))
      .def_property_readonly("dof", &RobotModel::dof)
      .def_property_readonly("joints", &RobotModel::joints)
      .def_property_readonly("moving_joints", &RobotModel::moving_joints)
      .def_property_readonly("link_names",
                             [](const RobotModel& model) {
                               std::vector<std::string> names;
                               for (const Link& link : model.links()) names.push_back(link.name);
                               return names;
                             })
      .def_property_readonly("geometry_links",
                             [](const RobotModel& model) {
                               std::vector<int> links;
                               for (const Geometry& g : model.geometries()) links.push_back(g.link);
                               return links;
                             })
      .def("adjacent_links", &adjacent_links, py::arg("a"), py::arg("b"),
           "True when links ``a`` and ``b`` are one rigid group or joined by one moving joint.")
      .def(
          "default_pairs", [](const RobotModel& model) { return to_table(default_pairs(model)); },
          "The geometry pairs checked by default, (pairs, 2): geometries of links that are not "
          "adjacent, and each obstacle against each link's geometry.")
      .def(
          "admit",
          [](const RobotModel& model, const Configurations& q, const py::object& limits,
             const Given<bool>& single) {
            if (!to_bool(single.value, "single")) {
              return admit_configurations(model, q, limit_mode(limits));
            }
            if (q.rows() != 1) {
              throw py::value_error("single=True takes one configuration, a (1, dof) table; got " +
                                    std::to_string(q.rows()) + " rows");
            }
            Configurations admitted(1, q.cols());
            admit_configuration(model, q.data(), q.cols(), limit_mode(limits), kSingleConfiguration,
                                admitted.data());
            return admitted;
          },
          py::arg("q"), py::arg("limits") = "raise", py::arg("single") = false,
          "The configurations (m, dof) checked and brought within the limits ('raise', 'clamp' "
          "or 'wrap'); ``single``: q's one row is a configuration given alone, whose messages "
          "name its values (q[j]) rather than its row.")
      .def(
          "forward_kinematics",
          [](const RobotModel& model, const Configurations& given) {
            // Admitted here too: this model's methods are public (Robot.model), and a NaN or an
            // angle beyond its limits would otherwise give poses without a word.
            const Configurations q = admit_configurations(model, given, LimitMode::raise);
            py::array_t<Scalar> transforms({static_cast<py::ssize_t>(q.rows()),
                                            static_cast<py::ssize_t>(model.links().size()),
                                            py::ssize_t{4}, py::ssize_t{4}});
            Scalar* out = transforms.mutable_data();
            {
              py::gil_scoped_release release;
              forward_kinematics(model, q, out);
            }
            return transforms;
          },
          py::arg("q"),
          "Every link's (4, 4) world transform at admitted configurations, (m, links, 4, 4).")
      .def(
          "geometry_poses",
          [](const RobotModel& model, const Configurations& given) {
            // Admitted here too: this model's methods are public (Robot.model), and a NaN or an
            // angle beyond its limits would otherwise give poses without a word.
            const Configurations q = admit_configurations(model, given, LimitMode::raise);
            py::array_t<Scalar> transforms({static_cast<py::ssize_t>(q.rows()),
                                            static_cast<py::ssize_t>(model.geometries().size()),
                                            py::ssize_t{4}, py::ssize_t{4}});
            Scalar* out = transforms.mutable_data();
            {
              py::gil_scoped_release release;
              geometry_poses(model, q, out);
            }
            return transforms;
          },
          py::arg("q"),
          "Every geometry's (4, 4) world transform at admitted configurations, (m, geometries, "
          "4, 4).")
      .def(
          "distances",
          [](const RobotModel& model, const Given<PairTable>& pairs, const Configurations& q,
             const Query& query, const py::object& threads) {
            const BatchSettings settings = settings_of(threads);
            const std::vector<GeometryPair> list = to_pairs(pairs);
            py::gil_scoped_release release;
            return robot_distances(model, list, q, query.options(), settings);
          },
          py::arg("pairs"), py::arg("q"), py::arg("query"), py::arg("threads") = py::none(),
          "Signed distances of geometry pairs (pairs, 2) at admitted configurations (m, dof).")
      .def(
          "check",
          [](const RobotModel& model, const Given<PairTable>& pairs, const Configurations& q,
             const Query& query, const py::object& threads, const Given<bool>& gradient,
             const Given<bool>& nearest) {
            const BatchSettings settings = settings_of(threads);
            const std::vector<GeometryPair> list = to_pairs(pairs);
            const bool with_gradient = to_bool(gradient.value, "gradient");
            const bool with_nearest = to_bool(nearest.value, "nearest");
            py::gil_scoped_release release;
            return robot_check(model, list, q, query.options(), settings, with_gradient,
                               with_nearest);
          },
          py::arg("pairs"), py::arg("q"), py::arg("query"), py::arg("threads") = py::none(),
          py::arg("gradient") = false, py::arg("nearest") = true,
          "The nearest pair per admitted configuration (m, dof), with d min_distance / dq when "
          "``gradient``; without ``nearest``, the verdict alone.")
      .def(
          "check_motion",
          [](const RobotModel& model, const Given<PairTable>& pairs, const Configurations& q0,
             const Configurations& q1, const Query& query, const Given<Scalar>& time_tolerance,
             const Given<int>& max_iterations, const py::object& threads) {
            const BatchSettings settings = settings_of(threads);
            const std::vector<GeometryPair> list = to_pairs(pairs);
            TimeOfImpactOptions options;
            options.query = query.options();
            options.time_tolerance = to_real(time_tolerance.value, "time_tolerance");
            options.max_iterations = to_count(max_iterations.value, "max_iterations", 1);
            py::gil_scoped_release release;
            return robot_check_motion(model, list, q0, q1, options, settings);
          },
          py::arg("pairs"), py::arg("q0"), py::arg("q1"), py::arg("query"),
          py::arg("time_tolerance") = kDefaultTimeTolerance,
          py::arg("max_iterations") = kDefaultMotionIterations, py::arg("threads") = py::none(),
          "The first contact of each straight joint-space motion from admitted q0 to q1 rows "
          "(m, dof; one row of either serves every motion), or a proof that there is none.");

  py::class_<SharedChecker>(m, "RobotChecker", R"doc(
A check of one configuration at a time with the pairs and options validated once (Robot.checker
wraps it): its buffers are kept from one call to the next. Keeps its model alive. Threads may
share it (the GIL is released while it checks): a call that finds its buffers busy uses its own.

Parameters
----------
model : RobotModel
pairs : int array, (pairs, 2)
    Geometry index pairs, as RobotModel.check takes them.
query : Query
    The pair queries' method and options.
nearest, gradient : bool
    As RobotModel.check.
)doc")
      .def(py::init([](const RobotModel& model, const Given<PairTable>& pairs, const Query& query,
                       const Given<bool>& nearest, const Given<bool>& gradient) {
             return new SharedChecker{RobotChecker(model, to_pairs(pairs), query.options(),
                                                   to_bool(nearest.value, "nearest"),
                                                   to_bool(gradient.value, "gradient")),
                                      {}};
           }),
           py::keep_alive<1, 2>(), py::arg("model"), py::arg("pairs"), py::arg("query"),
           py::arg("nearest") = true, py::arg("gradient") = false)
      .def(
          "check",
          [](SharedChecker& shared, const ConfigurationRef& q, const py::object& limits) {
            return checker_row_values(checked(shared, q, limits));
          },
          py::arg("q"), py::arg("limits") = "raise",
          "The configuration q (dof,) admitted ('raise', 'clamp' or 'wrap') and checked, "
          "answered as RobotCheck.row answers a row: (colliding, min_distance, lower_bound, "
          "certified, pair, point_a, point_b, normal, gradient or None).")
      .def(
          "collision_free",
          [](SharedChecker& shared, const ConfigurationRef& q, const py::object& limits) {
            const RobotCheckRow row = checked(shared, q, limits);
            return row.certified && !row.colliding;
          },
          py::arg("q"), py::arg("limits") = "raise",
          "True when q (dof,) is proven free of contact: no pair collides and the verdict is "
          "certified.")
      .def_property_readonly(
          "pair_count", [](const SharedChecker& shared) { return shared.checker.pairs().size(); })
      .def_property_readonly("nearest",
                             [](const SharedChecker& shared) { return shared.checker.nearest(); })
      .def_property_readonly(
          "gradient", [](const SharedChecker& shared) { return shared.checker.gradient(); });
}

}  // namespace swarmcollide::bindings
