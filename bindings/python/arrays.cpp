// NumPy ↔ Eigen helpers of the Python module.
#include "arrays.hpp"

#include <fmt/format.h>

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

JointRow to_row(const compensation::JointCommand& c) noexcept {
  return {c.t_s,
          {c.q_rad.x(), c.q_rad.y()},
          {c.qd_rad_s.x(), c.qd_rad_s.y()},
          {c.qdd_rad_s2.x(), c.qdd_rad_s2.y()},
          {c.target_m.x(), c.target_m.y()},
          {c.command_m.x(), c.command_m.y()},
          {c.force_N.x(), c.force_N.y()},
          {c.deflection_m.x(), c.deflection_m.y()},
          c.laser_on,
          c.power,
          c.outside_grid,
          static_cast<std::int32_t>(c.line)};
}

py::array RowWriter::array() const {
  ensure_record_dtypes();
  py::array_t<JointRow> out(static_cast<py::ssize_t>(rows.size()));
  std::copy(rows.begin(), rows.end(), out.mutable_data());
  return out;
}

}  // namespace stiffpath::python
