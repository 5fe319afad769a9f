// `stiffpath scan`: measures a laser-marked path on a scanned image (thesis §4.6) and prints its metrics.
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/image_io.hpp"
#include "stiffpath/vision/overlay.hpp"
#include "stiffpath/vision/scan.hpp"

namespace stiffpath::cli {

namespace {

struct ScanCliOptions {
  std::string image, shape = "line", overlay;
  double dpi = 1200, cutoff_mm = 1.0, trim_mm = 1.0;
  bool json = false;
  CLI::Option* dpi_option = nullptr;
};

int parse_sides(const std::string& shape) {
  if (shape == "line") return 1;
  if (shape == "triangle") return 3;
  if (shape.rfind("polyline:", 0) == 0) {
    const std::string n = shape.substr(9);
    if (!n.empty() && n.size() <= 2 && n.find_first_not_of("0123456789") == std::string::npos) {
      const int sides = std::stoi(n);
      if (sides >= 1 && sides <= 64) return sides;
    }
  }
  throw Error(fmt::format("--shape: expected line, triangle or polyline:N with N in 1..64, got '{}'", shape));
}

void run_scan(const ScanCliOptions& o) {
  vision::ScanOptions options;
  options.sides = parse_sides(o.shape);
  if (o.shape == "triangle") options.metrics.closure = evaluation::Closure::closed;
  if (o.shape == "line") options.metrics.closure = evaluation::Closure::open;
  if (!(o.cutoff_mm >= 0.0) || !(o.trim_mm >= 0.0)) throw Error("--spline-cutoff-mm and --corner-trim-mm must be >= 0");
  options.metrics.smoothing_cutoff_m = o.cutoff_mm * 1e-3;
  options.metrics.corner_trim_m = o.trim_mm * 1e-3;
  options.label = o.image;
  const auto dpi = o.dpi_option->count() > 0 ? std::optional<double>(o.dpi) : std::nullopt;
  const vision::ScanImage scan = vision::load_scan(o.image, dpi);
  vision::ScanResult result = vision::analyse_scan(scan.grey, scan.dpi, options);
  result.warnings.insert(result.warnings.begin(), scan.warnings.begin(), scan.warnings.end());
  if (!o.overlay.empty()) vision::write_image(o.overlay, vision::draw_overlay(scan.grey, result), scan.dpi);

  nlohmann::json out = vision::to_json(result);
  out["image"] = o.image;
  out["shape"] = o.shape;
  out["dpi_source"] = scan.dpi_source;
  if (o.json) {
    print_json(out);
    return;
  }
  fmt::print("{}: {} × {} px at {} dpi ({})\n", o.image, result.width_px, result.height_px, result.dpi, scan.dpi_source);
  fmt::print("length {:.4f} mm, deviation area {:.4f} mm², max deviation {:.4f} mm, straightness {:.4f} mm, width {:.4f} mm\n",
             out["length_mm"].get<double>(), out["deviation_area_mm2"].get<double>(), out["max_deviation_mm"].get<double>(),
             out["straightness_mm"].get<double>(), out["width_mm"].get<double>());
  if (out.contains("sides")) {
    for (std::size_t k = 0; k < out["sides"].size(); ++k) {
      const auto& s = out["sides"][k];
      fmt::print("  side {}: length {:.4f} mm, area {:.4f} mm², max deviation {:.4f} mm, width {:.4f} mm\n", k + 1,
                 s["length_mm"].get<double>(), s["deviation_area_mm2"].get<double>(), s["max_deviation_mm"].get<double>(),
                 s["width_mm"].get<double>());
    }
  }
  if (out.contains("corners")) {
    for (const auto& c : out["corners"]) {
      fmt::print("  corner at x = {:.4f} mm, y = {:.4f} mm, angle {:.3f}°\n", c["x_mm"].get<double>(), c["y_mm"].get<double>(),
                 c["angle_deg"].get<double>());
    }
  }
  for (const auto& w : result.warnings) fmt::print("warning: {}\n", w);
}

}  // namespace

void add_scan_command(CLI::App& app) {
  auto opts = std::make_shared<ScanCliOptions>();
  auto* cmd = app.add_subcommand("scan", "Measure a laser-marked path on a scan (thesis 4.6): length, deviation area, width");
  cmd->add_option("image", opts->image, "Scan (PNG, TIFF or JPEG; grey or colour; 8 or 16 bit)")->required();
  opts->dpi_option = cmd->add_option("--dpi", opts->dpi, "Resolution (dpi); overrides the file's metadata (default: metadata, else 1200)");
  cmd->add_option("--shape", opts->shape, "line, triangle or polyline:N")->capture_default_str();
  cmd->add_option("--overlay", opts->overlay, "Write a picture of the detected centre line, fitted line and spline (PNG)");
  cmd->add_option("--spline-cutoff-mm", opts->cutoff_mm, "Smoothing spline cutoff wavelength (mm)")->capture_default_str();
  cmd->add_option("--corner-trim-mm", opts->trim_mm, "Part of each side next to a corner left out (mm)")->capture_default_str();
  cmd->add_flag("--json", opts->json, "Print one JSON object with units in its keys");
  cmd->callback([opts] { run_scan(*opts); });
}

}  // namespace stiffpath::cli
