// Sections left out as outliers: a width far from the side's median (dust, gaps), or a centre off its neighbours' line.
#include <algorithm>
#include <cmath>

#include "side_trace.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

namespace {

double median(std::vector<double> v) { return core::median(std::move(v), core::MedianRule::upper_middle); }

}  // namespace

// A centre is measured from the side's line and compared with its neighbours' offsets, carried to it along
// their median slope, so that a side bending near its end, where the neighbours all lie to one side, is not
// taken for an outlier.
std::size_t reject_outliers(SideSections& side, const evaluation::Line2& line) {
  const ScanTuning& tuning = *side.tuning;
  std::vector<Section*> body;
  for (auto& s : side.sections) {
    if (s.body) body.push_back(&s);
  }
  std::vector<double> widths, width_deviations, centre_residuals(body.size());
  for (const auto* s : body) widths.push_back(s->width);
  const double median_width = median(widths);
  for (const double w : widths) width_deviations.push_back(std::abs(w - median_width));
  const double width_tolerance =
      std::max(tuning.width_tolerance * median_width, tuning.outlier_mads * core::kMadToSigma * median(width_deviations));
  std::vector<double> offset(body.size());
  for (std::size_t j = 0; j < body.size(); ++j) offset[j] = body[j]->centre - across_on_line(side.frame, line, body[j]->a + 0.5);
  const auto neighbours = static_cast<std::size_t>(tuning.outlier_neighbours);
  for (std::size_t k = 0; k < body.size(); ++k) {
    const std::size_t lo = k >= neighbours ? k - neighbours : 0, hi = std::min(body.size(), k + neighbours + 1);
    std::vector<double> carried, slopes;
    for (std::size_t j = lo; j + 1 < hi; ++j) slopes.push_back((offset[j + 1] - offset[j]) / (body[j + 1]->a - body[j]->a));
    const double slope = median(slopes);
    for (std::size_t j = lo; j < hi; ++j) carried.push_back(offset[j] - slope * (body[j]->a - body[k]->a));
    centre_residuals[k] = std::abs(offset[k] - median(carried));
  }
  const double centre_tolerance =
      std::max(tuning.min_centre_tolerance_px, tuning.outlier_mads * core::kMadToSigma * median(centre_residuals));
  std::size_t rejected = 0;
  for (std::size_t k = 0; k < body.size(); ++k) {
    body[k]->rejected = std::abs(body[k]->width - median_width) > width_tolerance || centre_residuals[k] > centre_tolerance;
    rejected += body[k]->rejected ? 1 : 0;
  }
  return rejected;
}

}  // namespace stiffpath::vision::detail
