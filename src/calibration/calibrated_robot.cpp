// calibrated_robot(): the identified values written as a robot file and a corrected model file.
#include "stiffpath/calibration/calibrated_robot.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <fmt/format.h>

#include "stiffpath/compensation/tip_modes.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot_json.hpp"

namespace stiffpath::calibration {

namespace {

// One correction for two rounds: at each point of a 9 × 9 grid over the second's square, the symmetric S with
// S·C·S = S₂·S₁·C·S₁·S₂ (C the base model: S = C^-½·(C^½·T·C^½)^½·C^-½, the unique positive definite solution),
// then sx = S11², sy = S22² and k = S12 each fitted linearly in the second's coordinates.
compliance::ComplianceCorrection composed(const compliance::ComplianceCorrection& first,
                                          const compliance::ComplianceCorrection& second, const compliance::Model& base) {
  compliance::ComplianceCorrection out = second;
  Eigen::MatrixXd A(81, 3);
  Eigen::VectorXd bx(81), by(81), bk(81);
  int row = 0;
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) {
      const double u = -1.0 + 0.25 * i, v = -1.0 + 0.25 * j;
      const Vec2 p = second.origin_m + Vec2(u * second.half_size_m.x(), v * second.half_size_m.y());
      const Mat2 C = base.compliance(p);
      const Mat2 M = second.matrix(p) * first.matrix(p);
      const Mat2 T = M * C * M.transpose();
      const Mat2 root = compensation::matrix_sqrt(C), inverse_root = root.inverse();
      const Mat2 S = inverse_root * compensation::matrix_sqrt(root * T * root) * inverse_root;
      A.row(row) << 1.0, u, v;
      bx[row] = S(0, 0) * S(0, 0);
      by[row] = S(1, 1) * S(1, 1);
      bk[row] = 0.5 * (S(0, 1) + S(1, 0));
      ++row;
    }
  }
  const auto qr = A.colPivHouseholderQr();
  const Eigen::Vector3d cx = qr.solve(bx), cy = qr.solve(by), ck = qr.solve(bk);
  out.sx = {cx[0], cx[1], cx[2]};
  out.sy = {cy[0], cy[1], cy[2]};
  out.sxy = {ck[0], ck[1], ck[2]};
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
    correction = composed(corrected->correction(), id.after.correction, corrected->base());
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
  // The laser's delays, where the plate determined them (its timing strokes switch the laser at speed); otherwise the
  // robot file's stay.
  double delay_ms[2] = {robot.laser_on_delay_s * 1e3, robot.laser_off_delay_s * 1e3};
  for (const auto& v : id.values) {
    const int k = v.name == "laser_on_delay_s" ? 0 : v.name == "laser_off_delay_s" ? 1 : -1;
    if (k >= 0 && v.determined) delay_ms[k] = v.after * 1e3;
  }
  if (delay_ms[0] != 0.0 || delay_ms[1] != 0.0) out.robot["laser"] = {{"on_delay_ms", delay_ms[0]}, {"off_delay_ms", delay_ms[1]}};
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
