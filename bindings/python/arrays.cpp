// NumPy ↔ Eigen helpers of the Python module.
#include "arrays.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "stiffpath/job/joint_record.hpp"

namespace stiffpath::python {

py::array_t<double, py::array::c_style | py::array::forcecast> pairs(const py::handle& value, const char* what) {
  auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!array) throw py::type_error(fmt::format("{}: expected an array of numbers", what));
  if (array.ndim() == 0 || array.shape(array.ndim() - 1) != 2) {
    throw py::value_error(fmt::format("{}: expected an array of shape (..., 2), got {} dimension(s) with last axis {}",
                                      what, array.ndim(), array.ndim() == 0 ? 0 : array.shape(array.ndim() - 1)));
  }
  return array;
}

std::vector<py::ssize_t> leading_shape(const py::array& pairs) {
  return {pairs.shape(), pairs.shape() + pairs.ndim() - 1};
}

py::array_t<double> new_pairs(const std::vector<py::ssize_t>& leading) {
  std::vector<py::ssize_t> shape = leading;
  shape.push_back(2);
  return py::array_t<double>(shape);
}

py::array_t<double> new_matrices(const std::vector<py::ssize_t>& leading) {
  std::vector<py::ssize_t> shape = leading;
  shape.push_back(2);
  shape.push_back(2);
  return py::array_t<double>(shape);
}

std::pair<py::array_t<double>, py::array_t<double>> broadcast_pairs(const py::handle& a, const char* a_name,
                                                                    const py::handle& b, const char* b_name) {
  const auto first = pairs(a, a_name);
  const auto second = pairs(b, b_name);
  py::sequence both;
  try {
    both = py::module_::import("numpy").attr("broadcast_arrays")(first, second);
  } catch (py::error_already_set&) {
    throw py::value_error(fmt::format("{} and {}: shapes cannot be broadcast together", a_name, b_name));
  }
  using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
  return {Array::ensure(both[0]), Array::ensure(both[1])};
}

py::array_t<double> points_array(const std::vector<Vec2>& points) {
  py::array_t<double> out({static_cast<py::ssize_t>(points.size()), py::ssize_t{2}});
  auto view = out.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < view.shape(0); ++i) {
    view(i, 0) = points[static_cast<std::size_t>(i)].x();
    view(i, 1) = points[static_cast<std::size_t>(i)].y();
  }
  return out;
}

py::array_t<double> point_array(const Vec2& point) {
  py::array_t<double> out(py::ssize_t{2});
  out.mutable_at(0) = point.x();
  out.mutable_at(1) = point.y();
  return out;
}

void ensure_record_dtypes() {
  static bool registered = false;  // guarded by the GIL
  if (registered) return;
  PYBIND11_NUMPY_DTYPE(TrajectoryRow, t_s, p_m, v_m_s, a_m_s2, j_m_s3, laser, power, line);
  PYBIND11_NUMPY_DTYPE(JointRow, t_s, q_rad, qd_rad_s, qdd_rad_s2, target_m, command_m, force_N, deflection_m, laser,
                       power, outside_grid, line);
  registered = true;
}

namespace {

template <class Row>
py::array_t<Row, py::array::c_style> records(const py::handle& value, const char* what, const char* dtype_name) {
  ensure_record_dtypes();
  auto array = py::array_t<Row, py::array::c_style>::ensure(value);
  if (!array) {
    PyErr_Clear();
    throw py::type_error(fmt::format("{}: expected a structured array of dtype stiffpath.{}", what, dtype_name));
  }
  return array;
}

}  // namespace

py::array_t<TrajectoryRow, py::array::c_style> trajectory_records(const py::handle& value, const char* what) {
  return records<TrajectoryRow>(value, what, "trajectory_dtype");
}

py::array_t<JointRow, py::array::c_style> joint_records(const py::handle& value, const char* what) {
  return records<JointRow>(value, what, "joints_dtype");
}

std::string describe_point(const Vec2& p_m) {
  return fmt::format("(x = {:.6g} mm, y = {:.6g} mm)", p_m.x() * 1e3, p_m.y() * 1e3);
}

motion::TrajectorySample to_sample(const TrajectoryRow& r) noexcept {
  motion::TrajectorySample s;
  s.t_s = r.t_s;
  s.position_m = Vec2(r.p_m[0], r.p_m[1]);
  s.velocity_m_s = Vec2(r.v_m_s[0], r.v_m_s[1]);
  s.acceleration_m_s2 = Vec2(r.a_m_s2[0], r.a_m_s2[1]);
  s.jerk_m_s3 = Vec2(r.j_m_s3[0], r.j_m_s3[1]);
  s.laser_on = r.laser;
  s.power = r.power;
  s.line = r.line;
  return s;
}

namespace {

// Where each field of the joint record (job::kJointFields) lives in a JointRow: its member of the same name. A member
// added to the table without a case here is a -Wswitch warning and an error thrown on first use.
template <class Row>  // JointRow or const JointRow
auto& number_cell(Row& r, const job::JointField& f) {
  switch (f.member) {
    case job::JointMember::t_s: return r.t_s;
    case job::JointMember::q_rad: return r.q_rad[f.component];
    case job::JointMember::qd_rad_s: return r.qd_rad_s[f.component];
    case job::JointMember::qdd_rad_s2: return r.qdd_rad_s2[f.component];
    case job::JointMember::power: return r.power;
    case job::JointMember::target_m: return r.target_m[f.component];
    case job::JointMember::command_m: return r.command_m[f.component];
    case job::JointMember::force_N: return r.force_N[f.component];
    case job::JointMember::laser:
    case job::JointMember::line: break;  // not doubles: below
  }
  throw std::logic_error(fmt::format("joints_dtype has no double member for joint field {}", f.csv_name));
}

void set_row(JointRow& r, const job::JointField& f, double v) {
  if (f.member == job::JointMember::laser) {
    r.laser = v != 0.0;
  } else if (f.member == job::JointMember::line) {
    r.line = static_cast<std::int32_t>(v);
  } else {
    number_cell(r, f) = v;
  }
}

double row_value(const JointRow& r, const job::JointField& f) {
  if (f.member == job::JointMember::laser) return r.laser ? 1.0 : 0.0;
  if (f.member == job::JointMember::line) return r.line;
  return number_cell(r, f);
}

}  // namespace

JointRow to_row(const compensation::JointCommand& c) {
  JointRow row{};
  for (const auto& f : job::kJointFields) set_row(row, f, job::value_of(c, f));
  // What a joint file does not hold: the predicted deflection and the grid flag.
  row.deflection_m[0] = c.deflection_m.x();
  row.deflection_m[1] = c.deflection_m.y();
  row.outside_grid = c.outside_grid;
  return row;
}

compensation::JointCommand to_command(const JointRow& row) {
  compensation::JointCommand c;
  for (const auto& f : job::kJointFields) job::set_value(c, f, row_value(row, f));
  c.deflection_m = Vec2(row.deflection_m[0], row.deflection_m[1]);
  c.outside_grid = row.outside_grid;
  return c;
}

py::dtype joint_file_dtype() {
  py::list names, formats, offsets;
  for (const auto& f : job::kJointFields) {
    names.append(py::str(std::string(f.si_name)));
    formats.append(f.binary_type == job::BinaryType::f64 ? "<f8" : f.binary_type == job::BinaryType::i32 ? "<i4" : "u1");
    offsets.append(f.offset_v2);
  }
  return py::dtype(names, formats, offsets, job::kBinaryRecordBytes);
}

py::tuple joint_file_fields() {
  py::list out;
  for (const auto& f : job::kJointFields) {
    out.append(py::make_tuple(std::string(f.csv_name), std::string(f.si_name), std::string(job::member_name(f.member)),
                              f.component, f.csv_per_si));
  }
  return py::tuple(out);
}

py::array RowWriter::array() const {
  ensure_record_dtypes();
  py::array_t<JointRow> out(static_cast<py::ssize_t>(rows.size()));
  std::copy(rows.begin(), rows.end(), out.mutable_data());
  return out;
}

}  // namespace stiffpath::python
