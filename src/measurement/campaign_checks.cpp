// Series grouping and the structural checks of a campaign (step 0 present, two or more loaded steps, …).
#include "stiffpath/measurement/campaign_checks.hpp"

#include <fmt/format.h>

#include <cmath>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::measurement {

std::vector<CampaignSeries> group_series(const Campaign& campaign) {
  std::vector<CampaignSeries> series;
  std::map<std::pair<std::string, int>, std::size_t> index;
  for (const auto& r : campaign.readings) {
    const auto key = std::make_pair(r.point, static_cast<int>(r.direction));
    auto it = index.find(key);
    if (it == index.end()) {
      it = index.emplace(key, series.size()).first;
      series.push_back({r.point, r.direction, {}});
    }
    series[it->second].steps[r.step].push_back(&r);
  }
  return series;
}

namespace {
[[noreturn]] void fail(const Campaign& c, int line, const std::string& message) {
  throw Error(SourceLocation{c.source, line, 0}, message);
}
}  // namespace

void validate_campaign(const Campaign& campaign) {
  if (campaign.readings.empty()) throw Error(SourceLocation{campaign.source}, "no readings in the campaign");
  std::map<std::string, const CampaignReading*> first_of_point;
  for (const auto& r : campaign.readings) {
    const auto [it, inserted] = first_of_point.emplace(r.point, &r);
    const CampaignReading& f = *it->second;
    if (!inserted && (std::abs(f.x_m - r.x_m) > 1e-9 || std::abs(f.y_m - r.y_m) > 1e-9)) {
      fail(campaign, r.line,
           fmt::format("column 'x_mm': point {} is at ({:.3f}, {:.3f}) mm here but at ({:.3f}, {:.3f}) mm on line {}", r.point,
                       units::m_to_mm(r.x_m), units::m_to_mm(r.y_m), units::m_to_mm(f.x_m), units::m_to_mm(f.y_m),
                       f.line));
    }
  }
  for (const auto& s : group_series(campaign)) {
    const int first_line = s.steps.begin()->second.front()->line;
    const std::string what = fmt::format("point {}, direction {}", s.point, to_string(s.direction));
    if (!s.steps.contains(0)) {
      fail(campaign, first_line,
           "column 'step': " + what + ": step 0 (the unloaded reference reading) is missing; displacements are relative to it");
    }
    if (s.steps.size() < 3) {
      fail(campaign, first_line,
           fmt::format("column 'step': {}: {} loaded step(s); at least two load steps besides step 0 are needed", what,
                       s.steps.size() - 1));
    }
    const double f0 = s.steps.at(0).front()->force_N;
    for (const auto& [step, readings] : s.steps) {
      const double f = readings.front()->force_N;
      for (const auto* r : readings) {
        if (std::abs(r->force_N - f) > 1e-6 * std::max(1.0, std::abs(f))) {
          fail(campaign, r->line,
               fmt::format("column 'force': {}, step {}: force {:.6g} N differs from {:.6g} N of reading on line {}", what, step,
                           r->force_N, f, readings.front()->line));
        }
      }
      if (step > 0 && !(f > f0)) {
        fail(campaign, readings.front()->line,
             fmt::format("column 'force': {}, step {}: force {:.6g} N does not exceed step 0's {:.6g} N", what, step, f, f0));
      }
    }
  }
}

}  // namespace stiffpath::measurement
