// Compliance model files: writing the JSON document and reading it back with field-by-field validation.
#include "stiffpath/compliance/model_file.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "stiffpath/compliance/corrected_model.hpp"
#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/compliance/physical_spline_model.hpp"
#include "stiffpath/compliance/tool_point.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/compliance/model_check.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/kinematics/robot_json.hpp"

#ifndef STIFFPATH_VERSION
#define STIFFPATH_VERSION "0.1.0"
#endif

namespace stiffpath::compliance {

nlohmann::json model_parameters(const Model& model) {
  // The models a file can hold, each with its own parameters; a wrapper adds its part to its base's.
  if (const auto* m = dynamic_cast<const CorrectedModel*>(&model)) return m->parameters();
  if (const auto* m = dynamic_cast<const ToolPointModel*>(&model)) return m->parameters();
  if (const auto* m = dynamic_cast<const PhysicalSplineModel*>(&model)) return m->parameters();
  if (const auto* m = dynamic_cast<const PhysicalModel*>(&model)) return m->parameters();
  if (const auto* m = dynamic_cast<const GridModel*>(&model)) return m->parameters();
  return {{"description", model.description()}};
}

namespace {
// The method key of a model file: a physical model of any order is "physical" with its `order` beside it.
std::string model_file_method(const Model& model) {
  const auto method = model.method();
  if (!method) throw Error("only a model fitted from a displacement table can be saved, not a " + model.description());
  switch (*method) {
    case FitMethod::physical_0:
    case FitMethod::physical_2: return "physical";
    default: return std::string(core::enum_name(*method));
  }
}
}  // namespace

nlohmann::json model_to_json(const Model& model, const Provenance& provenance) {
  nlohmann::json doc = {
      {"format", kModelFormat},
      {"version", kModelFormatVersion},
      {"method", model_file_method(model)},
      {"units", {{"length", "mm"}, {"compliance", "um/N"}, {"deflection", "um"}}},
      {"outside_policy", core::enum_name(model.outside_policy())},
      {"zero_force", core::enum_name(model.zero_force())},
      {"provenance",
       {{"source", provenance.source},
        {"sha256", provenance.sha256},
        {"rows", provenance.rows},
        {"force_convention", core::enum_name(provenance.convention)},
        {"method_selected_by", core::enum_name(provenance.selected_by)},
        {"created_by", std::string("stiffpath ") + STIFFPATH_VERSION}}},
  };
  if (!provenance.selection.is_null()) doc["provenance"]["selection"] = provenance.selection;
  if (provenance.geometry) {
    doc["robot"] = {{"name", provenance.robot},
                    {"geometry", kinematics::geometry_to_json(*provenance.geometry)},
                    {"geometry_sha256", kinematics::geometry_hash(*provenance.geometry)}};
  }
  doc.update(model_parameters(model));
  if (provenance.uncertainty) {
    const PredictionUncertainty& u = *provenance.uncertainty;
    const auto um2 = [](const std::array<double, 4>& v) {
      return nlohmann::json::array({v[0] * 1e12, v[1] * 1e12, v[2] * 1e12, v[3] * 1e12});
    };
    nlohmann::json points = nlohmann::json::array();
    if (u.field) {
      for (const Vec2& p : u.field->nodes()) points.push_back({p.x() * 1e3, p.y() * 1e3});
    }
    doc["uncertainty"] = {
        {"description", "variance of each C entry (c11, c12, c21, c22) = floor + scale * v(p), v the thin-plate kriging "
                        "variance of the measured points; a measurement adds the campaign's scatter; 95 % band = "
                        "Student t(degrees_of_freedom) standard deviations"},
        {"basis", to_string(u.basis)},
        {"symmetric", u.symmetric},
        {"floor_um2_per_N2", um2(u.floor_m2_per_N2)},
        {"scale_um2_per_N2", um2(u.scale_m2_per_N2)},
        {"campaign_sigma_um", {u.campaign_sigma_m.x() * 1e6, u.campaign_sigma_m.y() * 1e6}},
        {"held_out_points", u.held_out},
        {"degrees_of_freedom", u.degrees_of_freedom},
        {"smoothing", u.field ? u.field->smoothing() : 0.0},
        {"points_mm", points}};
  }
  return doc;
}

void save_model(const std::string& path, const Model& model, const Provenance& provenance) {
  core::write_file_atomically(path, model_to_json(model, provenance).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

namespace {
// A JSON array of exactly `n` finite numbers.
std::vector<double> numbers(const core::JsonObject& obj, std::string_view key, std::size_t n) {
  const auto& a = obj.array(key);
  if (n != 0 && a.size() != n) obj.fail(key, fmt::format("must have {} numbers, got {}", n, a.size()));
  std::vector<double> out;
  for (const auto& v : a) {
    if (!v.is_number()) obj.fail(key, "must contain only numbers, got " + core::shown(v));
    out.push_back(v.get<double>());
  }
  return out;
}

Mat2 matrix(const core::JsonObject& obj, std::string_view key) {
  const auto& a = obj.array(key);
  if (a.size() != 2 || !a[0].is_array() || !a[1].is_array() || a[0].size() != 2 || a[1].size() != 2) {
    obj.fail(key, "must be a 2x2 array [[a, b], [c, d]]");
  }
  Mat2 m;
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 2; ++c) {
      const auto& v = a[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
      if (!v.is_number()) obj.fail(key, "must contain only numbers, got " + core::shown(v));
      m(r, c) = v.get<double>();
    }
  }
  return m;
}

std::unique_ptr<Model> grid_model_from(const core::JsonObject& root, FitMethod method) {
  const core::JsonObject grid_obj = root.object("grid");
  Grid grid;
  for (double x : numbers(grid_obj, "x_mm", 0)) grid.xs.push_back(x * 1e-3);
  for (double y : numbers(grid_obj, "y_mm", 0)) grid.ys.push_back(y * 1e-3);
  for (const auto* lines : {&grid.xs, &grid.ys}) {
    if (lines->size() < 2 || !std::is_sorted(lines->begin(), lines->end()) ||
        std::adjacent_find(lines->begin(), lines->end()) != lines->end()) {
      grid_obj.fail(lines == &grid.xs ? "x_mm" : "y_mm", "must list at least two strictly increasing values");
    }
  }
  const auto& nodes_json = root.array("nodes");
  if (nodes_json.size() != grid.xs.size() * grid.ys.size()) {
    root.fail("nodes", fmt::format("must have {} entries for a {} x {} grid, got {}", grid.xs.size() * grid.ys.size(),
                                   grid.xs.size(), grid.ys.size(), nodes_json.size()));
  }
  std::vector<GridNode> nodes;
  for (std::size_t k = 0; k < nodes_json.size(); ++k) {
    const core::JsonObject n = root.element("nodes", k);
    const std::size_t i = k / grid.ys.size(), j = k % grid.ys.size();
    if (std::abs(n.number("x_mm") * 1e-3 - grid.xs[i]) > 1e-9 || std::abs(n.number("y_mm") * 1e-3 - grid.ys[j]) > 1e-9) {
      n.fail("x_mm", fmt::format("node is not at grid position ({}, {}) mm", grid.xs[i] * 1e3, grid.ys[j] * 1e3));
    }
    const auto offset = numbers(n, "offset_um", 2);
    nodes.push_back({n.string("point"), matrix(n, "C_um_per_N") * 1e-6, Vec2{offset[0], offset[1]} * 1e-6,
                     n.has("stats") ? n.raw()["stats"] : nlohmann::json::object()});
  }
  return std::make_unique<GridModel>(method, std::move(grid), std::move(nodes));
}

std::unique_ptr<PhysicalModel> physical_model_from(const core::JsonObject& root,
                                           const std::optional<kinematics::FiveBarGeometry>& recorded) {
  // Version 1 files give the thesis robot's link length; version 2 files their robot's geometry.
  kinematics::FiveBarGeometry geometry;
  if (root.has("link_length_mm")) {
    geometry = kinematics::FiveBarGeometry::thesis(root.positive("link_length_mm") * 1e-3);
  } else if (recorded) {
    geometry = *recorded;
  } else {
    root.fail("robot", "missing field (the physical model needs the robot's geometry)");
  }
  const double order_value = root.number("order");
  if (order_value != 0.0 && order_value != 1.0 && order_value != 2.0) root.fail("order", "must be 0, 1 or 2");
  const auto b = numbers(root, "bounds_mm", 4);
  if (!(b[1] > b[0] && b[3] > b[2])) root.fail("bounds_mm", "must be [x_min, x_max, y_min, y_max] with max > min");
  std::vector<std::array<double, 3>> coefficients;
  const auto& d = root.array("D_um_per_N");
  for (std::size_t k = 0; k < d.size(); ++k) {
    if (!d[k].is_array() || d[k].size() != 3) root.fail("D_um_per_N", fmt::format("entry {} must be [D11, D12, D22]", k));
    std::array<double, 3> c{};
    for (std::size_t m = 0; m < 3; ++m) {
      if (!d[k][m].is_number()) root.fail("D_um_per_N", "must contain only numbers, got " + core::shown(d[k][m]));
      c[m] = d[k][m].get<double>() * 1e-6;
    }
    coefficients.push_back(c);
  }
  const int order = static_cast<int>(order_value);
  const std::size_t expected = order == 0 ? 1 : order == 1 ? 3 : 6;
  if (coefficients.size() != expected) {
    root.fail("D_um_per_N", fmt::format("order {} needs {} entries, got {}", order, expected, coefficients.size()));
  }
  return std::make_unique<PhysicalModel>(geometry, GridBounds{b[0] * 1e-3, b[1] * 1e-3, b[2] * 1e-3, b[3] * 1e-3}, order,
                                         std::move(coefficients),
                                         root.has("stats") ? root.raw()["stats"] : nlohmann::json::object());
}

// `key` of `obj`: an array of `width`-number arrays (`count` of them, any count when 0), in the given scale.
std::vector<std::array<double, 3>> rows_of(const core::JsonObject& obj, const char* key, std::size_t width,
                                           std::size_t count, double scale) {
  const auto& a = obj.array(key);
  if (count != 0 && a.size() != count) obj.fail(key, fmt::format("must have {} entries, got {}", count, a.size()));
  std::vector<std::array<double, 3>> out;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!a[k].is_array() || a[k].size() != width) obj.fail(key, fmt::format("entry {} must be {} numbers", k, width));
    std::array<double, 3> row{};
    for (std::size_t m = 0; m < width; ++m) {
      if (!a[k][m].is_number() || !std::isfinite(a[k][m].get<double>())) {
        obj.fail(key, fmt::format("entry {} must contain only finite numbers, got {}", k, core::shown(a[k][m])));
      }
      row[m] = a[k][m].get<double>() * scale;
    }
    out.push_back(row);
  }
  return out;
}

std::unique_ptr<Model> physical_spline_model_from(const core::JsonObject& root,
                                                  const std::optional<kinematics::FiveBarGeometry>& recorded) {
  auto physical = physical_model_from(root, recorded);
  if (physical->order() != 1) root.fail("order", "a physical-spline model's physical part has order 1");
  const core::JsonObject r = root.object("residual_spline");
  ResidualSpline s;
  const auto [ox, oy] = r.pair("origin_mm");
  s.origin_m = Vec2(ox * 1e-3, oy * 1e-3);
  s.scale_m = r.positive("scale_mm") * 1e-3;
  s.smoothing = r.number("smoothing");
  if (!(s.smoothing >= 0.0)) r.fail("smoothing", "must be >= 0");
  for (const auto& q : rows_of(r, "nodes_unit", 2, 0, 1.0)) s.nodes.emplace_back(q[0], q[1]);
  if (s.nodes.size() < 3) r.fail("nodes_unit", "must list at least 3 nodes");
  s.weights = rows_of(r, "weights_um_per_N", 3, s.nodes.size(), 1e-6);
  const auto affine = rows_of(r, "affine_um_per_N", 3, 3, 1e-6);
  std::copy(affine.begin(), affine.end(), s.affine.begin());
  return std::make_unique<PhysicalSplineModel>(std::move(physical), std::move(s),
                                               root.has("stats") ? root.raw()["stats"] : nlohmann::json::object());
}

// The uncertainty block: every number finite and of its sign, the points as the field's nodes.
PredictionUncertainty uncertainty_from(const core::JsonObject& u) {
  PredictionUncertainty out;
  const std::string basis = u.string("basis");
  if (basis != "interpolation" && basis != "stationary") u.fail("basis", "must be \"interpolation\" or \"stationary\"");
  out.basis = basis == "interpolation" ? UncertaintyBasis::interpolation : UncertaintyBasis::stationary;
  if (!u.raw().contains("symmetric") || !u.raw().at("symmetric").is_boolean()) u.fail("symmetric", "must be true or false");
  out.symmetric = u.raw().at("symmetric").get<bool>();
  const auto four = [&](const char* key) {
    const auto& a = u.array(key);
    std::array<double, 4> v{};
    for (std::size_t c = 0; c < 4; ++c) {
      if (a.size() != 4 || !a[c].is_number() || !(a[c].get<double>() >= 0.0) || !std::isfinite(a[c].get<double>())) {
        u.fail(key, "must hold 4 finite variances >= 0 (c11, c12, c21, c22)");
      }
      v[c] = a[c].get<double>() * 1e-12;
    }
    return v;
  };
  out.floor_m2_per_N2 = four("floor_um2_per_N2");
  out.scale_m2_per_N2 = four("scale_um2_per_N2");
  const auto [sx, sy] = u.pair("campaign_sigma_um");
  if (!(sx >= 0.0 && sy >= 0.0)) u.fail("campaign_sigma_um", "must be two standard deviations >= 0");
  out.campaign_sigma_m = Vec2(sx * 1e-6, sy * 1e-6);
  out.held_out = static_cast<int>(u.non_negative("held_out_points"));
  const double dof = u.number("degrees_of_freedom");
  if (!(dof >= 1.0 && dof <= 1e6 && dof == std::floor(dof))) u.fail("degrees_of_freedom", "must be a whole number >= 1");
  out.degrees_of_freedom = static_cast<int>(dof);
  std::vector<Vec2> points;
  for (const auto& p : rows_of(u, "points_mm", 2, 0, 1e-3)) points.emplace_back(p[0], p[1]);
  if (!points.empty()) {
    try {
      out.field.emplace(points, u.non_negative("smoothing"));
    } catch (const Error& e) {
      u.fail("points_mm", e.message());
    }
  }
  return out;
}

// A calibration's correction over the model just read (corrected_model.hpp).
std::unique_ptr<Model> corrected_from(const core::JsonObject& c, std::unique_ptr<Model> base) {
  c.allow_only({"origin_mm", "half_size_mm", "sx", "sy", "sxy"});
  ComplianceCorrection correction;
  const auto [ox, oy] = c.pair("origin_mm");
  const auto [hx, hy] = c.pair("half_size_mm");
  if (!(hx > 0.0 && hy > 0.0)) c.fail("half_size_mm", "must be two positive lengths");
  correction.origin_m = {ox * 1e-3, oy * 1e-3};
  correction.half_size_m = {hx * 1e-3, hy * 1e-3};
  for (const std::string key : {"sx", "sy", "sxy"}) {
    if (key == "sxy" && !c.has(key)) continue;  // a correction without cross terms (written before they existed)
    const auto v = numbers(c, key.c_str(), 3);
    for (const double x : v) {
      if (std::abs(x) > 100.0) c.fail(key.c_str(), fmt::format("RANGE: coefficients must lie within ±100, got {}", x));
    }
    (key == "sx" ? correction.sx : key == "sy" ? correction.sy : correction.sxy) = {v[0], v[1], v[2]};
  }
  try {
    return std::make_unique<CorrectedModel>(std::shared_ptr<Model>(std::move(base)), correction);
  } catch (const Error& e) {
    c.fail("sx", e.message());
  }
}

// The robot block of a version-2 file: the geometry, checked against its recorded hash.
kinematics::FiveBarGeometry recorded_geometry(const core::JsonObject& robot) {
  const core::JsonObject g = robot.object("geometry");
  kinematics::FiveBarGeometry geometry;
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string side = i == 0 ? "left" : "right";
    const auto [x, y] = g.pair(side + "_actuator_mm");
    geometry.actuator_m[i] = {x * 1e-3, y * 1e-3};
    geometry.proximal_m[i] = g.positive(side + "_proximal_mm") * 1e-3;
    geometry.distal_m[i] = g.positive(side + "_distal_mm") * 1e-3;
  }
  const auto& elbows = g.array("elbows");
  if (elbows.size() != 2 || !elbows[0].is_number() || !elbows[1].is_number()) g.fail("elbows", "must be [+-1, +-1]");
  geometry.elbows = {elbows[0].get<double>() > 0 ? 1 : -1, elbows[1].get<double>() > 0 ? 1 : -1};
  geometry.assembly = g.sign("assembly");
  if (g.has("joint_zero_offsets_deg")) {
    const auto [d1, d2] = g.pair("joint_zero_offsets_deg");
    geometry.joint_zero_rad = {d1 * std::numbers::pi / 180.0, d2 * std::numbers::pi / 180.0};
  }
  if (robot.string("geometry_sha256") != kinematics::geometry_hash(geometry)) {
    robot.fail("geometry_sha256", "does not match the geometry recorded beside it (was the file edited?)");
  }
  return geometry;
}
}  // namespace

LoadedModel model_from_json(const core::JsonDocument& document) {
  const std::string& label = document.label;
  const core::JsonObject root(document);
  if (root.string("format") != kModelFormat) root.fail("format", std::string("must be \"") + kModelFormat + "\"");
  const double version = root.number("version");
  if (version != 1.0 && version != kModelFormatVersion) {
    root.fail("version", fmt::format("this stiffpath reads versions 1 and {}", kModelFormatVersion));
  }
  LoadedModel out;
  out.label = label;
  if (version >= 2.0) {
    const core::JsonObject robot = root.object("robot");
    out.provenance.robot = robot.string("name");
    out.provenance.geometry = recorded_geometry(robot);
  }
  const std::string method = root.string("method");
  if (method == "bilinear" || method == "symmetric") {
    out.model = grid_model_from(root, *core::find_enum<FitMethod>(method));
  } else if (method == "physical") {
    out.model = physical_model_from(root, out.provenance.geometry);
  } else if (method == "physical-spline") {
    out.model = physical_spline_model_from(root, out.provenance.geometry);
  } else {
    root.fail("method", "'" + method + "' is not one of bilinear, symmetric, physical, physical-spline");
  }
  if (root.has("correction")) out.model = corrected_from(root.object("correction"), std::move(out.model));
  // Physics bounds the model, whatever its parameters: wherever it serves, every compliance is finite,
  // within ±1000 um/N and positive definite (model_check.hpp).
  if (const auto defect = find_model_defect(*out.model)) {
    root.fail(method == "physical" ? "D_um_per_N" : method == "physical-spline" ? "residual_spline" : "nodes",
              defect->describe());
  }
  const auto parsed = [](const core::JsonObject& obj, const char* key, auto parse) {
    const std::string text = obj.string(key);
    try {
      return parse(text);
    } catch (const Error& e) {
      obj.fail(key, e.message());
    }
  };
  out.model->set_outside_policy(parsed(root, "outside_policy", core::parse_enum<OutsidePolicy>));
  out.model->set_zero_force(parsed(root, "zero_force", core::parse_enum<ZeroForce>));
  const core::JsonObject prov = root.object("provenance");
  out.provenance.source = prov.string("source");
  out.provenance.sha256 = prov.string("sha256");
  out.provenance.rows = prov.has("rows") ? prov.string("rows") : prov.has("mechanism") ? prov.string("mechanism") : "";
  out.provenance.convention = parsed(prov, "force_convention", core::parse_enum<ForceConvention>);
  if (prov.has("method_selected_by")) {
    out.provenance.selected_by = parsed(prov, "method_selected_by", core::parse_enum<MethodSelection>);
  }
  if (prov.has("selection")) out.provenance.selection = prov.raw()["selection"];
  if (root.has("uncertainty")) out.provenance.uncertainty = uncertainty_from(root.object("uncertainty"));
  return out;
}

LoadedModel load_model_file(const core::DataRef& file) {
  return model_from_json(core::parse_json_document(core::read_data(file, core::max_json_bytes), file.label()));
}

}  // namespace stiffpath::compliance
