// NumPy ↔ Eigen helpers of the Python module: (..., 2) point arrays, (..., 2, 2) matrices, the record dtypes.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <vector>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/kinematics/types.hpp"
#include "stiffpath/motion/planned_segment.hpp"

namespace stiffpath::python {

namespace py = pybind11;
using kinematics::Mat2;
using kinematics::Vec2;

//! A float64 array whose last axis has length 2 (a point, a force, joint angles); `what` names the
//! argument in the ValueError when the shape is wrong.
py::array_t<double, py::array::c_style | py::array::forcecast> pairs(const py::handle& value, const char* what);

//! The leading shape of a (..., 2) array (its shape without the last axis).
std::vector<py::ssize_t> leading_shape(const py::array& pairs);

//! A new (..., 2) or (..., 2, 2) float64 array of the given leading shape.
py::array_t<double> new_pairs(const std::vector<py::ssize_t>& leading);
py::array_t<double> new_matrices(const std::vector<py::ssize_t>& leading);

//! Broadcasts two (..., 2) arrays against each other (NumPy's rules), both C-contiguous float64.
std::pair<py::array_t<double>, py::array_t<double>> broadcast_pairs(const py::handle& a, const char* a_name,
                                                                    const py::handle& b, const char* b_name);

//! A list of points as an (N, 2) float64 array.
py::array_t<double> points_array(const std::vector<Vec2>& points);

//! One point as a (2,) float64 array.
py::array_t<double> point_array(const Vec2& point);

//! "(x = 222.132 mm, y = 37.5 mm)" for messages.
std::string describe_point(const Vec2& p_m);

//! One sample of a planned trajectory: the record type of stiffpath.trajectory_dtype. SI.
struct TrajectoryRow {
  double t_s;
  double p_m[2];
  double v_m_s[2];
  double a_m_s2[2];
  double j_m_s3[2];
  bool laser;
  double power;
  std::int32_t line;
};

//! One joint command: the record type of stiffpath.joints_dtype. SI.
struct JointRow {
  double t_s;
  double q_rad[2];
  double qd_rad_s[2];
  double qdd_rad_s2[2];
  double target_m[2];
  double command_m[2];
  double force_N[2];
  double deflection_m[2];
  bool laser;
  double power;
  bool outside_grid;
  std::int32_t line;
};

//! A trajectory record as the planner's sample; a joint command as a joint record and back (the joint file's fields
//! through job::kJointFields, then the deflection and the grid flag, which files do not hold).
motion::TrajectorySample to_sample(const TrajectoryRow& row) noexcept;
JointRow to_row(const compensation::JointCommand& command);
compensation::JointCommand to_command(const JointRow& row);

//! stiffpath.joint_file_dtype: the binary joint file's version-2 record (job::kJointFields at their offsets), for
//! np.fromfile(path, dtype=stiffpath.joint_file_dtype, offset=128). Needs NumPy.
py::dtype joint_file_dtype();
//! stiffpath.joint_file_fields: (csv_name, file_name, joints_field, component, csv_per_si) of every field.
py::tuple joint_file_fields();

//! A job's sink that keeps every command as a joint record (the joints array's records).
class RowWriter final : public job::JointWriter {
 public:
  void write(const compensation::JointCommand& command) override { rows.push_back(to_row(command)); }
  void finish() override {}
  //! The records as a new array of stiffpath.joints_dtype.
  [[nodiscard]] py::array array() const;
  std::vector<JointRow> rows;
};

//! Registers the record dtypes with pybind11 on first use (this imports NumPy, which `import stiffpath` does not:
//! NumPy's own import takes most of a second's fifth). Call before any array of these records is made or read.
void ensure_record_dtypes();

//! The argument as a C-contiguous array of trajectory or joint records (converting a compatible structured
//! array); TypeError naming `what` otherwise.
py::array_t<TrajectoryRow, py::array::c_style> trajectory_records(const py::handle& value, const char* what);
py::array_t<JointRow, py::array::c_style> joint_records(const py::handle& value, const char* what);

}  // namespace stiffpath::python
