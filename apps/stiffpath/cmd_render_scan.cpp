// `stiffpath render-scan`: draws a synthetic scan of a marked path and reports its ground truth.
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <numbers>
#include <sstream>

#include "commands.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/metrics_json.hpp"
#include "stiffpath/vision/image_io.hpp"
#include "stiffpath/vision/render.hpp"

namespace stiffpath::cli {

namespace {

struct RenderCliOptions {
  std::string output, shape = "line", vertices_mm, path_csv, truth;
  double length_mm = 100, side_mm = 40, angle_deg = 0, width_mm = 0.2, margin_mm = 2;
  double wiggle_mm = 0, wiggle_wavelength_mm = 10, wiggle_decay_mm = 40, trim_mm = 1.0;
  int sides = 1;
  bool json = false;
  vision::RenderOptions render;
};

std::vector<evaluation::Point2> parse_vertices(const std::string& text) {
  std::vector<evaluation::Point2> out;
  std::istringstream in(text);
  std::string pair;
  while (in >> pair) {
    const auto comma = pair.find(',');
    const auto x = core::parse_double(pair.substr(0, comma == std::string::npos ? 0 : comma));
    const auto y = core::parse_double(comma == std::string::npos ? "" : pair.substr(comma + 1));
    if (!x || !y) throw Error(fmt::format("--vertices-mm: expected 'x,y x,y ...' in mm, got '{}'", pair));
    out.emplace_back(*x * 1e-3, *y * 1e-3);
  }
  if (out.size() < 2) throw Error("--vertices-mm: a polyline needs at least two vertices");
  return out;
}

// A marked path from a CSV file with columns x_mm, y_mm (for example a simulated path), cut into sides.
std::pair<std::vector<std::vector<evaluation::Point2>>, bool> read_path(const std::string& path, int sides) {
  core::CsvReader csv(path);
  const auto cx = csv.column("x_mm"), cy = csv.column("y_mm");
  std::vector<evaluation::Point2> points;
  while (csv.next()) {
    const evaluation::Point2 p{csv.number(cx) * 1e-3, csv.number(cy) * 1e-3};
    if (points.empty() || (p - points.back()).norm() > 1e-12) points.push_back(p);  // a robot at rest repeats points
  }
  if (points.size() < 2) throw Error(SourceLocation{path, 0, 0}, "a path needs at least two points");
  // Drawn and measured as the polyline through the points, resampled every 20 µm of its length.
  const std::vector<evaluation::Point2> dense = vision::resample_path(points);
  if (sides == 1) return {{dense}, false};
  auto split = evaluation::split_polyline(dense, sides);
  return {split.sides, split.closed};
}

void run_render(RenderCliOptions& o) {
  o.render.mark_width_m = o.width_mm * 1e-3;
  o.render.rotation_rad = o.angle_deg * std::numbers::pi / 180.0;
  o.render.margin_m = o.margin_mm * 1e-3;
  if (!(o.trim_mm >= 0.0) || !std::isfinite(o.trim_mm)) throw Error(fmt::format("--corner-trim-mm must be >= 0, got {}", o.trim_mm));
  o.render.truth_options.corner_trim_m = o.trim_mm * 1e-3;
  const vision::Wiggle wiggle{o.wiggle_mm * 1e-3, o.wiggle_wavelength_mm * 1e-3, o.wiggle_decay_mm * 1e-3};
  std::vector<std::vector<evaluation::Point2>> sides;
  bool closed = false;
  if (!o.path_csv.empty()) {
    std::tie(sides, closed) = read_path(o.path_csv, o.sides);
  } else {
    vision::PathShape shape;
    if (o.shape == "line") {
      shape = vision::line_shape(o.length_mm * 1e-3);
    } else if (o.shape == "triangle") {
      shape = vision::triangle_shape(o.side_mm * 1e-3);
    } else if (o.shape == "polyline") {
      shape = {parse_vertices(o.vertices_mm), false};
    } else {
      throw Error(fmt::format("--shape: expected line, triangle or polyline, got '{}'", o.shape));
    }
    sides = vision::sample_shape(shape, wiggle);
    closed = shape.closed;
  }
  const vision::RenderedScan scan = vision::render_scan(sides, closed, o.render);
  vision::write_image(o.output, scan.image, scan.dpi);

  nlohmann::json truth = evaluation::to_json(scan.truth);
  truth["width_mm"] = evaluation::round_for_json(scan.mark_width_m * 1e3);
  truth["dpi"] = scan.dpi;
  truth["image"] = o.output;
  truth["image_px"] = {scan.image.cols, scan.image.rows};
  truth["seed"] = o.render.seed;
  if (!o.truth.empty()) core::write_file_atomically(o.truth, truth.dump(2) + "\n");
  if (o.json) {
    print_json(truth);
    return;
  }
  fmt::print("{}: {} × {} px at {} dpi\n", o.output, scan.image.cols, scan.image.rows, scan.dpi);
  fmt::print("truth: length {:.6f} mm, deviation area {:.6f} mm², max deviation {:.6f} mm, width {:.4f} mm\n",
             truth["length_mm"].get<double>(), truth["deviation_area_mm2"].get<double>(), truth["max_deviation_mm"].get<double>(),
             o.width_mm);
}

}  // namespace

void add_render_scan_command(CLI::App& app) {
  auto o = std::make_shared<RenderCliOptions>();
  auto* cmd = app.add_subcommand("render-scan", "Draw a synthetic scan of a laser-marked path and print its ground truth");
  cmd->add_option("output", o->output, "Image to write (.png, .tif, .jpg); the resolution is stored in it")->required();
  cmd->add_option("--shape", o->shape, "line, triangle or polyline (with --vertices-mm)")->capture_default_str();
  cmd->add_option("--length-mm", o->length_mm, "Line length (mm)")->capture_default_str();
  cmd->add_option("--side-mm", o->side_mm, "Triangle side (mm)")->capture_default_str();
  cmd->add_option("--vertices-mm", o->vertices_mm, "Polyline vertices 'x,y x,y ...' (mm, y down)");
  cmd->add_option("--path-csv", o->path_csv, "Draw this path instead (CSV with x_mm, y_mm columns, in marking order)");
  cmd->add_option("--sides", o->sides, "Sides of the --path-csv path, for its ground truth")->capture_default_str();
  cmd->add_option("--angle-deg", o->angle_deg, "Rotation of the path (deg, clockwise on screen)")->capture_default_str();
  cmd->add_option("--width-mm", o->width_mm, "Mark width = laser spot diameter (mm)")->capture_default_str();
  cmd->add_option("--margin-mm", o->margin_mm, "Paper around the mark (mm)")->capture_default_str();
  cmd->add_option("--wiggle-mm", o->wiggle_mm, "Initial amplitude of a decaying vibration (mm)")->capture_default_str();
  cmd->add_option("--wiggle-wavelength-mm", o->wiggle_wavelength_mm, "Its wavelength along the path (mm)")->capture_default_str();
  cmd->add_option("--wiggle-decay-mm", o->wiggle_decay_mm, "Its decay length along the path (mm)")->capture_default_str();
  cmd->add_option("--corner-trim-mm", o->trim_mm, "Corner trim of the ground truth's metrics (mm), as for scan")->capture_default_str();
  cmd->add_option("--dpi", o->render.dpi, "Resolution (dpi)")->capture_default_str();
  cmd->add_option("--blur-px", o->render.blur_px, "Scanner blur sigma (px)")->capture_default_str();
  cmd->add_option("--noise", o->render.noise, "Pixel noise sigma (fraction of full scale)")->capture_default_str();
  cmd->add_option("--texture", o->render.texture, "Paper fibre texture sigma (fraction)")->capture_default_str();
  cmd->add_option("--shading", o->render.shading, "Illumination falloff across the image (fraction)")->capture_default_str();
  cmd->add_option("--specks", o->render.specks, "Dust specks scattered over the image")->capture_default_str();
  cmd->add_option("--bit-depth", o->render.bit_depth, "8 or 16")->capture_default_str();
  cmd->add_flag("--colour", o->render.colour, "Write a colour (BGR) image");
  cmd->add_option("--seed", o->render.seed, "Seed of the noise, texture and specks")->capture_default_str();
  cmd->add_option("--truth", o->truth, "Also write the ground truth JSON to this file");
  cmd->add_flag("--json", o->json, "Print the ground truth as one JSON object");
  cmd->callback([o] { run_render(*o); });
}

}  // namespace stiffpath::cli
