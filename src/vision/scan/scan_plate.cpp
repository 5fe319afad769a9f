// A plate with several marks: every dark feature found once on the coarse grid, each measured or listed with the reason.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/evaluation/metrics_json.hpp"

namespace stiffpath::vision {

namespace {

// Groups boxes that stand closer to each other than the taller one's height (the letters of a word, the
// words of a label) into areas, by repeated merging.
std::vector<PlateLabelArea> group_labels(const std::vector<cv::Rect2d>& boxes) {
  std::vector<PlateLabelArea> areas;
  for (const auto& b : boxes) areas.push_back({b, 1});
  const auto gap = [](const cv::Rect2d& a, const cv::Rect2d& b) {
    const double dx = std::max({0.0, a.x - (b.x + b.width), b.x - (a.x + a.width)});
    const double dy = std::max({0.0, a.y - (b.y + b.height), b.y - (a.y + a.height)});
    return std::hypot(dx, dy);
  };
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < areas.size() && !merged; ++i) {
      for (std::size_t j = i + 1; j < areas.size() && !merged; ++j) {
        if (gap(areas[i].box_m, areas[j].box_m) > std::max(areas[i].box_m.height, areas[j].box_m.height)) continue;
        areas[i].box_m |= areas[j].box_m;
        areas[i].features += areas[j].features;
        areas.erase(areas.begin() + static_cast<std::ptrdiff_t>(j));
        merged = true;
      }
    }
  }
  return areas;
}

}  // namespace

PlateResult analyse_plate(const cv::Mat& grey, double dpi, const ScanOptions& options) {
  detail::check_scan_input(grey, dpi, options);
  const double px_per_m = dpi / 0.0254;
  const cv::Mat view = options.roi_px.empty() ? grey : grey(options.roi_px);
  const detail::CoarseGrid grid = detail::build_coarse_grid(view, options.tuning);
  const detail::Features features = detail::find_features(grid);
  // Each mark's own progress is the share of the marks still to do.
  ScanOptions each = options;
  double done = 0.3;
  const double share = features.list.empty() ? 0.0 : 0.7 / static_cast<double>(features.list.size());
  if (options.progress) {
    options.progress(done);
    each.progress = [&](double f) { options.progress(done + share * f); };
  }
  PlateResult plate;
  plate.dpi = dpi;
  plate.width_px = grey.cols;
  plate.height_px = grey.rows;
  plate.paper_noise = grid.sigma;
  const double cell = grid.cell;
  const cv::Mat paper = detail::paper_cells(grid);
  std::vector<cv::Rect2d> small;  // features too small to be marks
  for (const auto& f : features.list) {
    if (f.extent_px < options.min_mark_length_m * px_per_m) {
      ++plate.specks_ignored;
      done += share;
      continue;
    }
    const cv::Rect2d box((f.box.x * cell + options.roi_px.x) / px_per_m, (f.box.y * cell + options.roi_px.y) / px_per_m,
                         f.box.width * cell / px_per_m, f.box.height * cell / px_per_m);
    if (std::string artefact = detail::paper_artefact(grid, features, f, paper, px_per_m, options.tuning); !artefact.empty()) {
      plate.ignored.push_back({box, std::move(artefact)});
      done += share;
      continue;
    }
    if (f.extent_px < options.min_plate_mark_m * px_per_m) {
      small.push_back(box);
      done += share;
      continue;
    }
    PlateMark mark;
    mark.index = static_cast<int>(plate.marks.size()) + 1;
    mark.box_m = box;
    if (!f.border.empty()) {
      mark.reason = fmt::format("it touches the {} border of the {}, so it may be cut off", f.border,
                                options.roi_px.empty() ? "image" : "region");
    } else {
      try {
        mark.result = detail::measure_mark(view, grid, detail::mark_of(grid, features, f, options.tuning), px_per_m, each);
        mark.result.dpi = dpi;
        mark.result.width_px = grey.cols;
        mark.result.height_px = grey.rows;
        mark.measured = true;
      } catch (const Error& e) {
        mark.reason = e.message();
      }
    }
    plate.marks.push_back(std::move(mark));
    done += share;
    if (options.progress) options.progress(done);
  }
  plate.labels = group_labels(small);
  return plate;
}

nlohmann::json to_json(const PlateResult& plate) {
  using evaluation::round_for_json;
  nlohmann::json marks = nlohmann::json::array();
  int measured = 0;
  for (const auto& m : plate.marks) {
    nlohmann::json entry;
    if (m.measured) {
      entry = to_json(m.result);
      entry.erase("dpi");
      entry.erase("image_px");
      entry["shape"] = shape_name(m.result);
      ++measured;
    }
    entry["index"] = m.index;
    entry["box_mm"] = {round_for_json(units::m_to_mm(m.box_m.x)), round_for_json(units::m_to_mm(m.box_m.y)),
                       round_for_json(units::m_to_mm(m.box_m.width)), round_for_json(units::m_to_mm(m.box_m.height))};
    entry["status"] = m.measured ? "measured" : "skipped";
    if (!m.measured) entry["reason"] = m.reason;
    marks.push_back(std::move(entry));
  }
  nlohmann::json out;
  out["dpi"] = round_for_json(plate.dpi);
  out["image_px"] = {plate.width_px, plate.height_px};
  out["paper_noise"] = round_for_json(plate.paper_noise);
  out["specks_ignored"] = plate.specks_ignored;
  out["measured"] = measured;
  out["skipped"] = static_cast<int>(plate.marks.size()) - measured;
  out["marks"] = std::move(marks);
  nlohmann::json labels = nlohmann::json::array();
  for (const auto& l : plate.labels) {
    labels.push_back({{"box_mm", {round_for_json(units::m_to_mm(l.box_m.x)), round_for_json(units::m_to_mm(l.box_m.y)),
                                  round_for_json(units::m_to_mm(l.box_m.width)), round_for_json(units::m_to_mm(l.box_m.height))}},
                      {"features", l.features}});
  }
  out["labels"] = std::move(labels);
  nlohmann::json ignored = nlohmann::json::array();
  for (const auto& i : plate.ignored) {
    ignored.push_back({{"box_mm", {round_for_json(units::m_to_mm(i.box_m.x)), round_for_json(units::m_to_mm(i.box_m.y)),
                                   round_for_json(units::m_to_mm(i.box_m.width)), round_for_json(units::m_to_mm(i.box_m.height))}},
                       {"reason", i.reason}});
  }
  out["ignored"] = std::move(ignored);
  return out;
}

}  // namespace stiffpath::vision
