// Campaign processing: eq. 2.3 per reading, averaging per load step, displacement and tilt relative to step 0.
#include "stiffpath/measurement/process_campaign.hpp"

#include <cmath>
#include <vector>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/campaign_checks.hpp"

namespace stiffpath::measurement {

namespace {

// Mean and sample standard deviation of G and of the tilt angles over the readings of one step.
struct StepAverage {
  Vec3 g = Vec3::Zero();
  double rx = 0.0, ry = 0.0;
  Vec3 g_sd = Vec3::Zero();
  double rx_sd = 0.0, ry_sd = 0.0;
  int n = 0;
  double force_N = 0.0;
};

StepAverage average(const std::vector<const CampaignReading*>& readings, const ReplicaGeometry& geometry) {
  StepAverage a;
  a.n = static_cast<int>(readings.size());
  a.force_N = readings.front()->force_N;
  std::vector<Vec3> g;
  std::vector<Tilt> t;
  g.reserve(readings.size());
  t.reserve(readings.size());
  for (const auto* r : readings) {
    g.push_back(cg_point(r->U, r->L, geometry));
    t.push_back(tilt(r->U, r->L));
    a.g += g.back();
    a.rx += t.back().rx_rad;
    a.ry += t.back().ry_rad;
  }
  a.g /= a.n;
  a.rx /= a.n;
  a.ry /= a.n;
  if (a.n >= 2) {
    for (std::size_t i = 0; i < g.size(); ++i) {
      a.g_sd += (g[i] - a.g).cwiseAbs2();
      a.rx_sd += (t[i].rx_rad - a.rx) * (t[i].rx_rad - a.rx);
      a.ry_sd += (t[i].ry_rad - a.ry) * (t[i].ry_rad - a.ry);
    }
    const double dof = a.n - 1.0;
    a.g_sd = (a.g_sd / dof).cwiseSqrt();
    a.rx_sd = std::sqrt(a.rx_sd / dof);
    a.ry_sd = std::sqrt(a.ry_sd / dof);
  }
  return a;
}

}  // namespace

DisplacementTable process_campaign(const Campaign& campaign, const ProcessOptions& options) {
  if (!(options.geometry.ul_m > 0.0) || !(options.geometry.ug_m >= 0.0) || !std::isfinite(options.geometry.ug_m)) {
    throw Error(SourceLocation{campaign.source}, "replica geometry needs |UL| > 0 and |UG| >= 0");
  }
  if (options.nominal_step_N && !(*options.nominal_step_N > 0.0 && std::isfinite(*options.nominal_step_N))) {
    throw Error(SourceLocation{campaign.source}, "the nominal force step must be a positive number of N");
  }
  if (options.force_basis == ForceBasis::nominal && !campaign.has_nominal_forces && !options.nominal_step_N) {
    throw Error(SourceLocation{campaign.source},
                "nominal forces asked for, but the campaign names none: add a force_nominal_N column (the round load "
                "each step adds to step 0, N) or give the nominal step");
  }
  validate_campaign(campaign);
  DisplacementTable table;
  table.source = campaign.source;
  for (const auto& series : group_series(campaign)) {
    const StepAverage ref = average(series.steps.at(0), options.geometry);
    const CampaignReading& first = *series.steps.at(0).front();
    for (const auto& [step, readings] : series.steps) {
      if (step == 0) continue;
      const StepAverage cur = average(readings, options.geometry);
      DisplacementRow row;
      row.mechanism = options.mechanism;
      row.direction = series.direction;
      row.point = series.point;
      row.x_m = first.x_m;
      row.y_m = first.y_m;
      row.step = step;
      row.line = readings.front()->line;
      row.force_kgf = cur.force_N / units::standard_gravity_m_s2;
      const double measured = cur.force_N - ref.force_N;
      row.nominal_force_N = readings.front()->nominal_force_N ? *readings.front()->nominal_force_N
                            : options.nominal_step_N          ? step * *options.nominal_step_N
                                                              : measured;
      row.force_N = options.force_basis == ForceBasis::measured ? measured : row.nominal_force_N;
      const Vec3 d = cur.g - ref.g;
      row.dx_m = d.x();
      row.dy_m = d.y();
      row.dz_m = d.z();
      row.rx_rad = cur.rx - ref.rx;
      row.ry_rad = cur.ry - ref.ry;
      if (cur.n >= 2) {
        row.spread = ReadingSpread{cur.n, cur.g_sd.x(), cur.g_sd.y(), cur.g_sd.z(), cur.rx_sd, cur.ry_sd};
      }
      table.rows.push_back(std::move(row));
    }
  }
  return table;
}

}  // namespace stiffpath::measurement
