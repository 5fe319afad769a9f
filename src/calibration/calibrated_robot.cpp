// calibrated_robot(): the identified values written as a robot file and a corrected model file.
#include "stiffpath/calibration/calibrated_robot.hpp"

#include <Eigen/QR>
#include <fmt/format.h>

#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot_json.hpp"

namespace stiffpath::calibration {

namespace {

// The linear fit of sx1·sx2 (and sy1·sy2) over the second correction's normalised square, in its coordinates.
compliance::ComplianceCorrection composed(const compliance::ComplianceCorrection& first,
                                          const compliance::ComplianceCorrection& second) {
  compliance::ComplianceCorrection out = second;
  Eigen::MatrixXd A(81, 3);
  Eigen::VectorXd bx(81), by(81);
  int row = 0;
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) {
      const double u = -1.0 + 0.25 * i, v = -1.0 + 0.25 * j;
      const Vec2 p = second.origin_m + Vec2(u * second.half_size_m.x(), v * second.half_size_m.y());
      const Vec2 f = first.factors(p).cwiseProduct(second.factors(p));
      A.row(row) << 1.0, u, v;
      bx[row] = f.x();
      by[row] = f.y();
      ++row;
    }
  }
  const Eigen::Vector3d cx = A.colPivHouseholderQr().solve(bx), cy = A.colPivHouseholderQr().solve(by);
  out.sx = {cx[0], cx[1], cx[2]};
  out.sy = {cy[0], cy[1], cy[2]};
  return out;
}

nlohmann::json vec_mm(const Vec2& p) { return nlohmann::json::array({p.x() * 1e3, p.y() * 1e3}); }

}  // namespace

CalibratedRobot calibrated_robot(const kinematics::Robot& robot, const compliance::LoadedModel& base,
                                 const Identification& id, const std::string& model_file_name) {
  if (!base.model) throw Error("calibration: no compliance model to correct");
  // The base model without any earlier plate's correction, and the correction to apply over it.
  std::shared_ptr<compliance::Model> original;
  compliance::ComplianceCorrection correction = id.after.correction;
  if (const auto* corrected = dynamic_cast<const compliance::CorrectedModel*>(base.model.get())) {
    correction = composed(corrected->correction(), id.after.correction);
    // A copy of the base of the earlier round: re-read from its own JSON, so the result owns its model.
    const nlohmann::json doc = compliance::model_to_json(corrected->base(), base.provenance);
    original = std::shared_ptr<compliance::Model>(
        compliance::model_from_json(core::parse_json_document(doc.dump(), base.label)).model.release());
  } else {
    const nlohmann::json doc = compliance::model_to_json(*base.model, base.provenance);
    original = std::shared_ptr<compliance::Model>(
        compliance::model_from_json(core::parse_json_document(doc.dump(), base.label)).model.release());
  }
  const compliance::CorrectedModel model(original, correction);

  CalibratedRobot out;
  out.model = compliance::model_to_json(model, base.provenance);
  out.robot = kinematics::to_json(robot);
  out.robot["name"] = robot.name + "-cal";
  out.robot["description"] = fmt::format("{}, calibrated from a plate of its own marks (stiffpath calibrate fit)",
                                         robot.description.empty() ? robot.name : robot.description);
  out.robot["tip_damping_ratio"] = id.after.damping_ratio;
  out.robot["tip_frequency_scale"] = id.after.frequency_scale;
  out.robot["laser"] = {{"on_delay_ms", id.after.laser_on_delay_s * 1e3}, {"off_delay_ms", id.after.laser_off_delay_s * 1e3}};
  out.robot["compliance"] = {{"model", model_file_name}};
  return out;
}

nlohmann::json identification_json(const Identification& id) {
  nlohmann::json values = nlohmann::json::array();
  for (const auto& v : id.values) {
    values.push_back({{"name", v.name}, {"before", v.before}, {"after", v.after}, {"sigma", v.sigma}, {"determined", v.determined}});
  }
  nlohmann::json marks = nlohmann::json::array();
  for (const auto& m : id.marks) {
    marks.push_back({{"id", m.id},
                     {"rms_before_um", m.rms_before_m * 1e6},
                     {"rms_after_um", m.rms_after_m * 1e6},
                     {"max_before_um", m.max_before_m * 1e6},
                     {"max_after_um", m.max_after_m * 1e6},
                     {"end_before_um", m.end_before_m * 1e6},
                     {"end_after_um", m.end_after_m * 1e6}});
  }
  nlohmann::json scales = nlohmann::json::array();
  for (const auto& s : id.scales) {
    scales.push_back({{"point_mm", vec_mm(s.point_m)},
                      {"scale", {s.scale.x(), s.scale.y()}},
                      {"sigma", {s.sigma.x(), s.sigma.y()}}});
  }
  return {{"description", "values before (the robot file's) and after, with their standard uncertainty; a value the "
                          "plate does not determine is held (determined: false). scale: the deflection per unit "
                          "acceleration (m·C) after over before, along x and y, at each station"},
          {"values", values},
          {"stop", core::to_string(id.stop)},
          {"iterations", id.iterations},
          {"residuals", id.residuals},
          {"rms_before_um", id.rms_before_m * 1e6},
          {"rms_after_um", id.rms_after_m * 1e6},
          {"scales", scales},
          {"marks", marks}};
}

}  // namespace stiffpath::calibration
