// `stiffpath render-scan`: draws a synthetic scan of a marked path, or of a plate of marks, and reports its ground truth.
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <numbers>
#include <sstream>

#include "bounded.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "vision_resources.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/distinct_files.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/metrics_json.hpp"
#include "stiffpath/vision/io/image_io.hpp"
#include "stiffpath/vision/io/resolution.hpp"
#include "stiffpath/vision/render/plate.hpp"
#include "stiffpath/vision/render/render.hpp"

namespace stiffpath::cli {

namespace {

struct RenderCliOptions {
  std::string output, shape = "line", vertices_mm, path_csv, plate, truth;
  double length_mm = 100, side_mm = 40, angle_deg = 0, width_mm = 0.2, margin_mm = 2;
  double wiggle_mm = 0, wiggle_wavelength_mm = 10, wiggle_decay_mm = 40, trim_mm = 1.0;
  int sides = 1;
  bool json = false, quiet = false;
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

// Renders into the output file: a PNG row band by row band (never the whole image in memory), other
// formats from the whole image.
template <class Render>
auto render_to(const RenderCliOptions& o, int width, int height, const Render& render) {
  const std::string ext = std::filesystem::path(o.output).extension().string();
  if (ext == ".png" || ext == ".PNG") {
    const int type = CV_MAKETYPE(o.render.bit_depth == 8 ? CV_8U : CV_16U, o.render.colour ? 3 : 1);
    vision::PngRowWriter png(o.output, width, height, type, o.render.dpi);
    auto result = render([&](int, const cv::Mat& rows) { png.write(rows); });
    png.commit();
    return result;
  }
  vision::encode_image(cv::Mat(1, 1, CV_8U), o.output, o.render.dpi);  // refuse an unknown extension before the work
  auto result = render(vision::RowSink{});
  vision::write_image(o.output, result.image, result.dpi);
  return result;
}

// The plate's truth, in the image's frame (mm from its top-left corner, y down): each mark's metrics and box,
// each fiducial's centre, and where the page lies (image = offset + linear · page).
nlohmann::json plate_truth(const vision::RenderedPlate& plate, const vision::Plate& page) {
  using evaluation::round_for_json;
  nlohmann::json marks = nlohmann::json::array();
  for (std::size_t k = 0; k < plate.marks.size(); ++k) {
    nlohmann::json m = evaluation::to_json(plate.marks[k].truth);
    const auto& b = plate.marks[k].box_m;
    m["index"] = k + 1;
    if (!plate.marks[k].id.empty()) m["id"] = plate.marks[k].id;
    m["box_mm"] = {round_for_json(b.x * 1e3), round_for_json(b.y * 1e3), round_for_json(b.width * 1e3), round_for_json(b.height * 1e3)};
    marks.push_back(std::move(m));
  }
  nlohmann::json fiducials = nlohmann::json::array();
  for (std::size_t k = 0; k < plate.fiducials_m.size(); ++k) {
    const auto& f = page.fiducials[k];
    fiducials.push_back({{"index", k + 1},
                         {"centre_mm", {round_for_json(plate.fiducials_m[k].x() * 1e3), round_for_json(plate.fiducials_m[k].y() * 1e3)}},
                         {"radius_mm", round_for_json(f.shape.ring_radius_m * 1e3)},
                         {"cross", f.shape.cross}});
  }
  const auto& a = plate.placement;
  nlohmann::json out;
  out["page_mm"] = {round_for_json(page.width_m * 1e3), round_for_json(page.height_m * 1e3)};
  out["page_to_image"] = {{"linear", {{round_for_json(a.linear(0, 0)), round_for_json(a.linear(0, 1))},
                                      {round_for_json(a.linear(1, 0)), round_for_json(a.linear(1, 1))}}},
                          {"offset_mm", {round_for_json(a.offset.x() * 1e3), round_for_json(a.offset.y() * 1e3)}},
                          {"mirrored", a.mirrored()}};
  out["labels"] = page.labels.size();
  out["marks"] = std::move(marks);
  out["fiducials"] = std::move(fiducials);
  return out;
}

void render(RenderCliOptions& o);

void run_render(RenderCliOptions& o) {
  core::check_distinct_files({{"--plate", o.plate}, {"--path-csv", o.path_csv}}, {{"output", o.output}, {"--truth", o.truth}});
  within_resources(o.output, "rendering the scan", 0.0, [&] { render(o); });
}

void render(RenderCliOptions& o) {
  o.render.mark_width_m = o.width_mm * 1e-3;
  o.render.rotation_rad = o.angle_deg * std::numbers::pi / 180.0;
  o.render.margin_m = o.margin_mm * 1e-3;
  if (!(o.trim_mm >= 0.0) || !std::isfinite(o.trim_mm)) throw Error(fmt::format("--corner-trim-mm must be >= 0, got {}", o.trim_mm));
  o.render.truth_options.corner_trim_m = o.trim_mm * 1e-3;
  Progress progress("render-scan", o.quiet);
  o.render.progress = progress.callback();

  nlohmann::json truth;
  int width = 0, height = 0;
  if (!o.plate.empty()) {
    const vision::Plate page = vision::load_plate(o.plate);
    const cv::Size size = vision::plate_image_size(page, o.render);  // the budget, before any work
    width = size.width, height = size.height;
    const auto plate = render_to(o, width, height, [&](const vision::RowSink& sink) {
      return sink ? vision::render_plate(page, o.render, sink) : vision::render_plate(page, o.render);
    });
    truth = plate_truth(plate, page);
  } else {
    std::vector<std::vector<evaluation::Point2>> sides;
    bool closed = false;
    if (!o.path_csv.empty()) {
      auto mark = vision::load_mark_csv(o.path_csv, o.sides);
      sides = std::move(mark.sides);
      closed = mark.closed;
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
      try {
        sides = vision::sample_shape(shape, {o.wiggle_mm * 1e-3, o.wiggle_wavelength_mm * 1e-3, o.wiggle_decay_mm * 1e-3});
      } catch (const Error& e) {  // the budget: say which options asked for it
        throw Error(fmt::format("--shape {} with --wiggle-mm {} and --wiggle-wavelength-mm {}: {}", o.shape, o.wiggle_mm,
                                o.wiggle_wavelength_mm, e.message()));
      }
      closed = shape.closed;
    }
    const cv::Size size = vision::rendered_size(sides, o.render);
    width = size.width, height = size.height;
    const auto scan = render_to(o, width, height, [&](const vision::RowSink& sink) {
      return sink ? vision::render_scan(sides, closed, o.render, sink) : vision::render_scan(sides, closed, o.render);
    });
    truth = evaluation::to_json(scan.truth);
  }
  progress.finish();
  truth["width_mm"] = evaluation::round_for_json(o.width_mm);
  truth["dpi"] = o.render.dpi;
  truth["image"] = o.output;
  truth["image_px"] = {width, height};
  truth["seed"] = o.render.seed;
  if (!o.truth.empty()) core::write_file_atomically(o.truth, truth.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  if (o.json) {
    print_json(truth);
    return;
  }
  fmt::print("{}: {} × {} px at {} dpi\n", o.output, width, height, o.render.dpi);
  if (truth.contains("marks")) {
    for (const auto& m : truth["marks"]) {
      fmt::print("truth of mark {} (box x {:.2f} mm, y {:.2f} mm, {:.2f} × {:.2f} mm): length {:.6f} mm, deviation area {:.6f} mm²\n",
                 m["index"].get<int>(), m["box_mm"][0].get<double>(), m["box_mm"][1].get<double>(), m["box_mm"][2].get<double>(),
                 m["box_mm"][3].get<double>(), m["length_mm"].get<double>(), m["deviation_area_mm2"].get<double>());
    }
    return;
  }
  fmt::print("truth: length {:.6f} mm, deviation area {:.6f} mm², max deviation {:.6f} mm, width {:.4f} mm\n",
             truth["length_mm"].get<double>(), truth["deviation_area_mm2"].get<double>(), truth["max_deviation_mm"].get<double>(),
             o.width_mm);
}

}  // namespace

void add_render_scan_command(CLI::App& app) {
  auto o = std::make_shared<RenderCliOptions>();
  auto* cmd = app.add_subcommand("render-scan", "Draw a synthetic scan of a laser-marked path (or a plate of marks) and print its ground truth");
  cmd->add_option("output", o->output, "Image to write (.png, .tif, .jpg); the resolution is stored in it")->check(output_name())->required();
  cmd->add_option("--shape", o->shape, "line, triangle or polyline (with --vertices-mm)")->capture_default_str();
  cmd->add_option("--length-mm", o->length_mm, "Line length (mm)")->capture_default_str()
      ->check(within(0.01, 2000, "mm"));
  cmd->add_option("--side-mm", o->side_mm, "Triangle side (mm)")->capture_default_str()
      ->check(within(0.01, 2000, "mm"));
  cmd->add_option("--vertices-mm", o->vertices_mm, "Polyline vertices 'x,y x,y ...' (mm, y down)");
  cmd->add_option("--path-csv", o->path_csv, "Draw this path instead (CSV with x_mm, y_mm columns, in marking order)");
  cmd->add_option("--sides", o->sides, "Sides of the --path-csv path, for its ground truth")->capture_default_str()
      ->check(within(1, 64, ""));
  cmd->add_option("--plate", o->plate, "Draw a page of marks and labels described in this JSON file (docs/vision.md)");
  cmd->add_option("--angle-deg", o->angle_deg, "Rotation of the path (deg, clockwise on screen)")->capture_default_str()
      ->check(within(-3600, 3600, "deg"));
  cmd->add_option("--width-mm", o->width_mm, "Mark width = laser spot diameter (mm)")->capture_default_str()
      ->check(within(0.001, 50, "mm"));
  cmd->add_option("--margin-mm", o->margin_mm, "Paper around the mark (mm)")->capture_default_str()
      ->check(within(0, 1000, "mm"));
  cmd->add_option("--wiggle-mm", o->wiggle_mm, "Initial amplitude of a decaying vibration (mm)")->capture_default_str()
      ->check(within(0, 100, "mm"));
  cmd->add_option("--wiggle-wavelength-mm", o->wiggle_wavelength_mm, "Its wavelength along the path (mm)")->capture_default_str()
      ->check(within(0.001, 10000.0, "mm"));
  cmd->add_option("--wiggle-decay-mm", o->wiggle_decay_mm, "Its decay length along the path (mm)")->capture_default_str()
      ->check(within(0.001, 1000000.0, "mm"));
  cmd->add_option("--corner-trim-mm", o->trim_mm, "Corner trim of the ground truth's metrics (mm), as for scan")->capture_default_str()
      ->check(within(0, 1000, "mm"));
  cmd->add_option("--dpi", o->render.dpi, "Resolution (dpi)")->capture_default_str()
      ->check(within(vision::kMinScanDpi, vision::kMaxScanDpi, "dpi"));
  cmd->add_option("--blur-px", o->render.blur_px, "Scanner blur sigma (px)")->capture_default_str()
      ->check(within(0, 1000, "px"));
  cmd->add_option("--noise", o->render.noise, "Pixel noise sigma (fraction of full scale)")->capture_default_str()
      ->check(within(0, 1, ""));
  cmd->add_option("--texture", o->render.texture, "Paper fibre texture sigma (fraction)")->capture_default_str()
      ->check(within(0, 1, ""));
  cmd->add_option("--shading", o->render.shading, "Illumination falloff across the image (fraction)")->capture_default_str()
      ->check(within(0, 1, ""));
  cmd->add_option("--specks", o->render.specks, "Dust specks scattered over the image")->capture_default_str()
      ->check(within(0, 1000000.0, ""));
  cmd->add_option("--bit-depth", o->render.bit_depth, "8 or 16")->capture_default_str()
      ->check(within(8, 16, ""));
  cmd->add_flag("--colour", o->render.colour, "Write a colour (BGR) image");
  cmd->add_option("--seed", o->render.seed, "Seed of the noise, texture and specks")->capture_default_str();
  cmd->add_option("--truth", o->truth, "Also write the ground truth JSON to this file")->check(output_name());
  cmd->add_flag("--json", o->json, "Print the ground truth as one JSON object");
  cmd->add_flag("--quiet", o->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([o] { run_render(*o); });
}

}  // namespace stiffpath::cli
