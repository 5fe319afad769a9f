// `stiffpath scan`: measures a laser-marked path on a scanned image (thesis §4.6), or every mark of a plate, and prints the metrics.
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <iterator>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "vision_resources.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/distinct_files.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/io/resolution.hpp"
#include "stiffpath/vision/scan/overlay.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::cli {

namespace {

struct ScanCliOptions {
  std::string image, shape = "line", overlay, roi, centre_line_csv;
  double dpi = 1200, cutoff_mm = 1.0, trim_mm = 1.0, min_mark_mm = 10.0;
  bool json = false, all_marks = false, quiet = false;
  CLI::Option* dpi_option = nullptr;
  CLI::Option* shape_option = nullptr;
};

// "--roi X,Y,W,H" in mm from the image's top-left corner, or with a unit suffix "…mm" / "…px".
struct Roi {
  double v[4] = {0.0, 0.0, 0.0, 0.0};  // x, y, width, height
  bool px = false;  // in pixels rather than mm
};

Roi parse_roi(const std::string& text) {
  std::string body = text;
  bool px = false;
  if (body.size() > 2 && (body.ends_with("px") || body.ends_with("mm"))) {
    px = body.ends_with("px");
    body.resize(body.size() - 2);
  }
  Roi roi{{0, 0, 0, 0}, px};
  std::size_t start = 0;
  for (int i = 0; i < 4; ++i) {
    const std::size_t comma = body.find(',', start);
    if ((i < 3) != (comma != std::string::npos)) throw Error(fmt::format("--roi: expected X,Y,W,H (mm, or px with a px suffix), got '{}'", text));
    const std::string field = body.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const auto value = core::parse_double(field);
    if (!value) throw Error(fmt::format("--roi: expected X,Y,W,H (mm, or px with a px suffix), got '{}': '{}' is not a number", text, field));
    if (*value < 0 || (i >= 2 && *value <= 0)) throw Error(fmt::format("--roi: '{}': X and Y must be numbers >= 0, W and H numbers > 0", text));
    roi.v[i] = *value;
    start = comma + 1;
  }
  return roi;
}

cv::Rect roi_pixels(const Roi& roi, const std::string& text, const vision::ScanImage& scan) {
  const double per = roi.px ? 1.0 : scan.dpi / 25.4;
  const double x0 = std::round(roi.v[0] * per), y0 = std::round(roi.v[1] * per);
  const double x1 = std::round((roi.v[0] + roi.v[2]) * per), y1 = std::round((roi.v[1] + roi.v[3]) * per);
  if (x1 > scan.grey.cols || y1 > scan.grey.rows) {
    throw Error(fmt::format("--roi {}: reaches beyond the image ({} × {} px, {:.1f} × {:.1f} mm at {} dpi)", text, scan.grey.cols,
                            scan.grey.rows, scan.grey.cols * 25.4 / scan.dpi, scan.grey.rows * 25.4 / scan.dpi, scan.dpi));
  }
  return {static_cast<int>(x0), static_cast<int>(y0), static_cast<int>(x1 - x0), static_cast<int>(y1 - y0)};
}

void print_result(const nlohmann::json& out, const std::string& indent) {
  fmt::print("{}length {:.4f} mm, deviation area {:.4f} mm², max deviation {:.4f} mm, straightness {:.4f} mm, width {:.4f} mm\n", indent,
             out["length_mm"].get<double>(), out["deviation_area_mm2"].get<double>(), out["max_deviation_mm"].get<double>(),
             out["straightness_mm"].get<double>(), out["width_mm"].get<double>());
  if (out.contains("sides")) {
    for (std::size_t k = 0; k < out["sides"].size(); ++k) {
      const auto& s = out["sides"][k];
      fmt::print("{}  side {}: length {:.4f} mm, area {:.4f} mm², max deviation {:.4f} mm, width {:.4f} mm\n", indent, k + 1,
                 s["length_mm"].get<double>(), s["deviation_area_mm2"].get<double>(), s["max_deviation_mm"].get<double>(),
                 s["width_mm"].get<double>());
    }
  }
  if (out.contains("corners")) {
    for (const auto& c : out["corners"]) {
      fmt::print("{}  corner at x = {:.4f} mm, y = {:.4f} mm, angle {:.3f}°\n", indent, c["x_mm"].get<double>(), c["y_mm"].get<double>(),
                 c["angle_deg"].get<double>());
    }
  }
  for (const auto& w : out["warnings"]) fmt::print("{}warning: {}\n", indent, w.get<std::string>());
}

// One row per centre-line point of every side of every mark measured: mark (1 for a single scan, the plate's
// mark index with --all-marks), side (1-based), the point's position in mm of the scan.
std::string centre_line_csv(const std::string& image, const std::vector<std::pair<int, const vision::ScanResult*>>& marks) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "# centre lines measured on {}: x_mm, y_mm in {}; each side's points in marking order, "
                 "a free end's first or last point being the path's end (the round spot's centre)\nmark,side,x_mm,y_mm\n", image,
                 vision::kCentreLineFrame);
  for (const auto& [mark, result] : marks) {
    for (std::size_t k = 0; k < result->sides.size(); ++k) {
      for (const auto& p : result->sides[k].centres) fmt::format_to(std::back_inserter(out), "{},{},{:.4f},{:.4f}\n", mark, k + 1, p.x() * 1e3, p.y() * 1e3);
    }
  }
  return fmt::to_string(out);
}

// An output may never be the scan it is made from.
void check_not_the_image(const std::string& output, const std::string& option, const std::string& image) {
  if (output.empty()) return;
  std::error_code ec;
  const bool same = std::filesystem::equivalent(output, image, ec) ||
                    std::filesystem::weakly_canonical(output, ec) == std::filesystem::weakly_canonical(image, ec);
  if (same) throw Error(fmt::format("{} {}: that is the scan being measured; an input is never an output", option, output));
}

void run_scan(const ScanCliOptions& o) {
  core::check_distinct_files({{"image", o.image}}, {{"--overlay", o.overlay}, {"--centre-line-csv", o.centre_line_csv}});
  vision::ScanOptions options;
  if (o.shape_option->count() > 0) {
    const vision::ScanShape shape = vision::parse_scan_shape(o.shape, "--shape");
    options.sides = shape.sides;
    options.metrics.closure = shape.closure;
  } else {
    options.sides = o.all_marks ? 0 : 1;  // a line, or any shape on a plate; closure found on the scan
  }
  if (!(o.cutoff_mm >= 0.0) || !(o.trim_mm >= 0.0)) throw Error("--spline-cutoff-mm and --corner-trim-mm must be >= 0");
  if (!(o.min_mark_mm > 0.0) || !std::isfinite(o.min_mark_mm)) throw Error("--min-mark-mm must be positive");
  options.metrics.smoothing_cutoff_m = o.cutoff_mm * 1e-3;
  options.metrics.corner_trim_m = o.trim_mm * 1e-3;
  options.min_plate_mark_m = o.min_mark_mm * 1e-3;
  options.label = o.image;
  const Roi roi = o.roi.empty() ? Roi{} : parse_roi(o.roi);  // parsed before the image is read: a typo fails fast
  check_not_the_image(o.overlay, "--overlay", o.image);
  check_not_the_image(o.centre_line_csv, "--centre-line-csv", o.image);
  const auto dpi = o.dpi_option->count() > 0 ? std::optional<double>(o.dpi) : std::nullopt;
  Progress progress("scan", o.quiet);
  progress.update(0.0, "reading the image");
  vision::ScanImage scan;
  within_resources(o.image, "reading the scan", 0.0, [&] { scan = vision::load_scan(o.image, dpi); });
  if (!o.roi.empty()) options.roi_px = roi_pixels(roi, o.roi, scan);
  options.progress = progress.callback();
  // The analysis holds the image and about 1.1 × its 8-bit pixels more (docs/vision.md), the program ~50 MiB.
  const double needs = 2.1 * static_cast<double>(scan.grey.total()) + 50e6;

  nlohmann::json out;
  std::string csv;
  within_resources(o.image, fmt::format("measuring the {} × {} px scan", scan.grey.cols, scan.grey.rows), needs, [&] {
    if (o.all_marks) {
      const vision::PlateResult plate = vision::analyse_plate(scan.grey, scan.dpi, options);
      progress.finish();
      if (!o.overlay.empty()) vision::write_image(o.overlay, vision::draw_plate_overlay(scan.grey, plate), scan.dpi);
      out = vision::to_json(plate);
      out["warnings"] = scan.warnings;
      std::vector<std::pair<int, const vision::ScanResult*>> measured;
      for (const auto& m : plate.marks) {
        if (m.measured) measured.emplace_back(m.index, &m.result);
      }
      if (!o.centre_line_csv.empty()) csv = centre_line_csv(o.image, measured);
    } else {
      vision::ScanResult result = vision::analyse_scan(scan.grey, scan.dpi, options);
      progress.finish();
      result.warnings.insert(result.warnings.begin(), scan.warnings.begin(), scan.warnings.end());
      if (!o.overlay.empty()) vision::write_image(o.overlay, vision::draw_overlay(scan.grey, result), scan.dpi);
      out = vision::to_json(result);
      out["shape"] = vision::shape_name(result);
      if (!o.centre_line_csv.empty()) csv = centre_line_csv(o.image, {{1, &result}});
    }
  });
  if (!o.centre_line_csv.empty()) core::write_file_atomically(o.centre_line_csv, csv);
  out["image"] = o.image;
  out["dpi_source"] = scan.dpi_source;
  if (!o.roi.empty()) {
    const cv::Rect& r = options.roi_px;
    const double mm = 25.4 / scan.dpi;
    out["roi_mm"] = {r.x * mm, r.y * mm, r.width * mm, r.height * mm};
  }
  if (o.json) {
    print_json(out);
    return;
  }
  fmt::print("{}: {} × {} px at {} dpi ({})\n", o.image, scan.grey.cols, scan.grey.rows, scan.dpi, scan.dpi_source);
  if (!o.all_marks) {
    print_result(out, "");
    return;
  }
  for (const auto& w : out["warnings"]) fmt::print("warning: {}\n", w.get<std::string>());
  int letters = 0;
  for (const auto& l : out["labels"]) letters += l["features"].get<int>();
  fmt::print("{} marks measured, {} skipped; {} label areas ({} features smaller than {} mm) not measured; {} specks ignored\n",
             out["measured"].get<int>(), out["skipped"].get<int>(), out["labels"].size(), letters, o.min_mark_mm,
             out["specks_ignored"].get<int>());
  for (const auto& m : out["marks"]) {
    const auto& b = m["box_mm"];
    fmt::print("mark {} at x {:.2f}..{:.2f} mm, y {:.2f}..{:.2f} mm: ", m["index"].get<int>(), b[0].get<double>(),
               b[0].get<double>() + b[2].get<double>(), b[1].get<double>(), b[1].get<double>() + b[3].get<double>());
    if (m["status"] == "measured") {
      fmt::print("{}\n", m["shape"].get<std::string>());
      print_result(m, "  ");
    } else {
      fmt::print("skipped: {}\n", m["reason"].get<std::string>());
    }
  }
}

}  // namespace

void add_scan_command(CLI::App& app) {
  auto opts = std::make_shared<ScanCliOptions>();
  auto* cmd = app.add_subcommand("scan", "Measure a laser-marked path on a scan (thesis 4.6): length, deviation area, width");
  cmd->add_option("image", opts->image, "Scan (PNG, TIFF or JPEG; grey or colour; 8 or 16 bit)")->required();
  opts->dpi_option = cmd->add_option("--dpi", opts->dpi, "Resolution (dpi); overrides the file's metadata (default: metadata, else 1200)")
      ->check(within(vision::kMinScanDpi, vision::kMaxScanDpi, "dpi"));
  opts->shape_option = cmd->add_option("--shape", opts->shape, "line, triangle, polyline:N or any (default line; any with --all-marks)");
  cmd->add_option("--roi", opts->roi, "Measure only the region X,Y,W,H: mm from the image's top-left corner, or pixels with a px suffix (10,20,80,30px)");
  cmd->add_flag("--all-marks", opts->all_marks, "Measure every mark on the scan (a plate): one result per mark with its bounding box");
  cmd->add_option("--min-mark-mm", opts->min_mark_mm, "With --all-marks: smaller dark features are listed as labels, not measured (mm)")->capture_default_str()
      ->check(within(0.001, 1000, "mm"));
  cmd->add_option("--overlay", opts->overlay, "Write a picture of the detected centre line, fitted line and spline (PNG)")->check(output_name());
  cmd->add_option("--centre-line-csv", opts->centre_line_csv,
                  "Write every measured side's centre line: mark,side,x_mm,y_mm in mm of the scan from its image's top-left corner, y down")
      ->check(output_name());
  cmd->add_option("--spline-cutoff-mm", opts->cutoff_mm, "Smoothing spline cutoff wavelength (mm)")->capture_default_str()
      ->check(within(0, 10000.0, "mm"));
  cmd->add_option("--corner-trim-mm", opts->trim_mm, "Part of each side next to a corner left out (mm)")->capture_default_str()
      ->check(within(0, 1000, "mm"));
  cmd->add_flag("--json", opts->json, "Print one JSON object with units in its keys");
  cmd->add_flag("--quiet", opts->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([opts] { run_scan(*opts); });
}

}  // namespace stiffpath::cli
