// The compensation model of the twin: a virtual CMM campaign on C_true, processed and fitted as the thesis did.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/process_campaign.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::simulation {

measurement::DisplacementTable virtual_campaign_table(const compliance::Model& truth, const kinematics::Robot& robot,
                                                      const CampaignFitOptions& options) {
  const measurement::DisplacementTable own = compliance::robot_table(robot);
  measurement::DisplacementTable exact = measurement::linear_truth(own);
  for (auto& row : exact.rows) {
    const compliance::Vec2 F = row.force_N * compliance::Vec2(measurement::direction_x(row.direction),
                                                              measurement::direction_y(row.direction));
    const compliance::Vec2 d = truth.compliance({row.x_m, row.y_m}) * F;
    row.dx_m = d.x();
    row.dy_m = d.y();
  }
  measurement::VirtualCampaignOptions campaign;
  campaign.noise_sigma_m = options.noise_sigma_m;
  campaign.seed = options.seed;
  campaign.step0_kgf = measurement::step0_load_kgf(own);  // the robot's own reference load, none without one
  measurement::ProcessOptions process;
  process.mechanism = robot.compliance.rows;
  if (robot.replica) {
    campaign.geometry = process.geometry = {robot.replica->ug_m, robot.replica->ul_m};
  } else {
    campaign.geometry = process.geometry = {0.0, 0.1};  // no replica: G itself is read (U = G)
  }
  measurement::DisplacementTable measured =
      measurement::process_campaign(measurement::simulate_campaign(exact, campaign), process);
  measured.source = fmt::format("virtual campaign on C_true ({}, seed {})", robot.name, options.seed);
  return measured;
}

std::shared_ptr<const compliance::Model> fit_compensation_model(const compliance::Model& truth,
                                                                const kinematics::Robot& robot,
                                                                const CampaignFitOptions& options) {
  const auto table = virtual_campaign_table(truth, robot, options);
  const std::optional<compliance::FitMethod> method = options.method ? options.method : robot.compliance.method;
  std::shared_ptr<compliance::Model> model =
      compliance::fit_model(table, robot.compliance.rows, method, compliance::ForceConvention::measured, robot).model;
  return model;
}

}  // namespace stiffpath::simulation
