// `stiffpath plot compliance|cv`: compliance figures (gnuplot, SVG and PNG).
#include <cctype>
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/displacement_table.hpp"
#include "stiffpath/report/compliance_plots.hpp"

namespace stiffpath::cli {

namespace {
struct PlotOptions {
  std::string robot;
  compliance::ModelRequest request;
  std::string data;  // default: the robot's table
  std::string dir = "plots";
  double margin_mm = 0.0;
};

std::filesystem::path output_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(SourceLocation{dir}, "cannot create output directory: " + ec.message());
  return dir;
}

std::string safe_name(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
  }
  return name;
}
}  // namespace

void add_plot_command(CLI::App& app) {
  auto o = std::make_shared<PlotOptions>();
  auto* plot = app.add_subcommand("plot", "Figures with gnuplot (SVG and PNG)");
  plot->require_subcommand(1);

  auto* comp = plot->add_subcommand("compliance", "Largest compliance over the workspace with principal directions");
  add_robot_flag(comp, o->robot);
  add_model_flags(comp, o->request);
  comp->add_option("--margin-mm", o->margin_mm, "Also show this far outside the grid")->capture_default_str();
  comp->add_option("-o,--output-dir", o->dir, "Directory for the figures")->capture_default_str();
  comp->callback([o] {
    const auto robot = load_robot_flag(o->robot);
    const auto loaded = compliance::load_robot_model(robot, o->request);
    const std::string name =
        "compliance_" + safe_name(!o->request.model.empty() ? std::filesystem::path(o->request.model).stem().string()
                                                            : robot.name + "-" + loaded.model->method());
    const double largest = report::plot_compliance_map(
        output_dir(o->dir), name, *loaded.model,
        fmt::format("{} ({}, {}): largest compliance", robot.name, loaded.label, loaded.model->method()),
        o->margin_mm * 1e-3);
    fmt::print("wrote {0}/{1}.svg and {0}/{1}.png (largest compliance {2:.3f} um/N)\n", o->dir, name, largest);
  });

  auto* cv = plot->add_subcommand("cv", "Measured vs predicted deflections of every model (leave-one-out)");
  cv->add_option("data", o->data, "Displacement table CSV, or 'thesis' (default: the robot's own table)");
  add_robot_flag(cv, o->robot);
  cv->add_option("-o,--output-dir", o->dir, "Directory for the figures")->capture_default_str();
  cv->callback([o] {
    const auto robot = load_robot_flag(o->robot);
    const auto table = o->data.empty() ? compliance::robot_table(robot)
                                       : measurement::load_displacement_table(table_ref(o->data)).filter(robot.compliance.rows);
    auto report = compliance::cross_validate(compliance::group_by_point(table, compliance::ForceConvention::measured),
                                             robot.geometry, table.source);
    report.rows = robot.compliance.rows;
    report.robot = robot.name;
    const std::string name = "cv_" + safe_name(robot.name);
    report::plot_cross_validation(output_dir(o->dir), name, report);
    fmt::print("wrote {0}/{1}.svg and {0}/{1}.png\n", o->dir, name);
  });
}

}  // namespace stiffpath::cli
