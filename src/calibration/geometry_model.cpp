// The geometry calibration's parameter vector: five-bar geometry and instrument frame, and the readings they predict.
#include "stiffpath/calibration/geometry_model.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::calibration {

namespace {
using P = GeometryParameter;
constexpr int idx(P p) { return static_cast<int>(p); }

constexpr const char* kNames[kGeometryParameters] = {
    "left_actuator_x_mm", "left_actuator_y_mm", "right_actuator_x_mm", "right_actuator_y_mm",
    "left_proximal_mm",   "right_proximal_mm",  "left_distal_mm",      "right_distal_mm",
    "theta1_zero_deg",    "theta2_zero_deg",    "instrument_rotation_x_deg", "instrument_rotation_y_deg",
    "instrument_rotation_z_deg", "instrument_x_mm", "instrument_y_mm", "instrument_z_mm"};

bool is_angle(int k) {
  return k == idx(P::theta1_zero) || k == idx(P::theta2_zero) || (k >= idx(P::instrument_rotation_x) && k <= idx(P::instrument_rotation_z));
}

// The margin of the fit's five-bar: none, so that every pose the instrument read is evaluated.
const kinematics::SingularityMargin kNoMargin{0.0, 1e300, 0.0};
}  // namespace

const char* parameter_name(int k) noexcept { return k >= 0 && k < kGeometryParameters ? kNames[k] : "?"; }

double parameter_unit_factor(int k) noexcept { return is_angle(k) ? 180.0 / std::numbers::pi : 1e3; }

Eigen::Matrix3d rotation_of(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (!(angle > 0.0)) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

GeometryModel::GeometryModel(const kinematics::Robot& nominal, const Eigen::Matrix3d& start_rotation)
    : nominal_(nominal), r0_(start_rotation) {}

Eigen::VectorXd GeometryModel::pack(const kinematics::FiveBarGeometry& g, const InstrumentFrame& frame) const {
  Eigen::VectorXd x(kGeometryParameters);
  x << g.actuator_m[0].x(), g.actuator_m[0].y(), g.actuator_m[1].x(), g.actuator_m[1].y(), g.proximal_m[0],
      g.proximal_m[1], g.distal_m[0], g.distal_m[1], g.joint_zero_rad[0], g.joint_zero_rad[1], 0.0, 0.0, 0.0,
      frame.translation_m.x(), frame.translation_m.y(), frame.translation_m.z();
  const Eigen::AngleAxisd relative(r0_.transpose() * frame.rotation);
  x.segment<3>(idx(P::instrument_rotation_x)) = relative.angle() * relative.axis();
  return x;
}

kinematics::FiveBarGeometry GeometryModel::geometry(const Eigen::VectorXd& x) const {
  kinematics::FiveBarGeometry g = nominal_.geometry;
  g.actuator_m = {kinematics::Vec2(x(idx(P::left_actuator_x)), x(idx(P::left_actuator_y))),
                  kinematics::Vec2(x(idx(P::right_actuator_x)), x(idx(P::right_actuator_y)))};
  g.proximal_m = {x(idx(P::left_proximal)), x(idx(P::right_proximal))};
  g.distal_m = {x(idx(P::left_distal)), x(idx(P::right_distal))};
  g.joint_zero_rad = {x(idx(P::theta1_zero)), x(idx(P::theta2_zero))};
  return g;
}

InstrumentFrame GeometryModel::instrument(const Eigen::VectorXd& x) const {
  InstrumentFrame f;
  f.rotation = r0_ * rotation_of(x.segment<3>(idx(P::instrument_rotation_x)));
  f.translation_m = x.segment<3>(idx(P::instrument_x));
  return f;
}

kinematics::Vec2 GeometryModel::end_point(const kinematics::FiveBarGeometry& g, const kinematics::Vec2& q) {
  return kinematics::FiveBar(g, kNoMargin).forward(q);
}

Eigen::Vector3d GeometryModel::reading(const Eigen::VectorXd& x, const kinematics::Vec2& q) const {
  return instrument(x).to_instrument(end_point(geometry(x), q));
}

}  // namespace stiffpath::calibration
