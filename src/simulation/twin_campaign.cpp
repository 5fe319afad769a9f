// The compensation model of the twin: a virtual CMM campaign on C_true, processed and fitted as the thesis did.
#include <fmt/format.h>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/process_campaign.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::simulation {

measurement::DisplacementTable virtual_campaign_table(const compliance::Model& truth, const std::string& build,
                                                      const CampaignFitOptions& options) {
  const auto thesis = measurement::load_displacement_table("thesis").filter(build);
  if (thesis.rows.empty()) throw Error(fmt::format("no thesis data for build '{}'", build));
  measurement::DisplacementTable exact = measurement::linear_truth(thesis);
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
  measurement::ProcessOptions process;
  process.mechanism = build;
  measurement::DisplacementTable measured =
      measurement::process_campaign(measurement::simulate_campaign(exact, campaign), process);
  measured.source = fmt::format("virtual campaign on C_true ({}, seed {})", build, options.seed);
  return measured;
}

std::shared_ptr<const compliance::Model> fit_compensation_model(const compliance::Model& truth, const std::string& build,
                                                                const CampaignFitOptions& options) {
  const auto table = virtual_campaign_table(truth, build, options);
  std::shared_ptr<compliance::Model> model = compliance::fit_model(table, build, options.method).model;
  return model;
}

}  // namespace stiffpath::simulation
