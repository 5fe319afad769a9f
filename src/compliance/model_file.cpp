// Compliance model files: writing the JSON document and reading it back with field-by-field validation.
#include "stiffpath/compliance/model_file.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"

#ifndef STIFFPATH_VERSION
#define STIFFPATH_VERSION "0.1.0"
#endif

namespace stiffpath::compliance {

nlohmann::json model_to_json(const Model& model, const Provenance& provenance) {
  nlohmann::json doc = {
      {"format", kModelFormat},
      {"version", kModelFormatVersion},
      {"method", model.method()},
      {"units", {{"length", "mm"}, {"compliance", "um/N"}, {"deflection", "um"}}},
      {"outside_policy", to_string(model.outside_policy())},
      {"zero_force", to_string(model.zero_force())},
      {"provenance",
       {{"source", provenance.source},
        {"sha256", provenance.sha256},
        {"mechanism", provenance.mechanism},
        {"force_convention", to_string(provenance.convention)},
        {"created_by", std::string("stiffpath ") + STIFFPATH_VERSION}}},
  };
  doc.update(model.parameters());
  return doc;
}

void save_model(const std::string& path, const Model& model, const Provenance& provenance) {
  core::write_file_atomically(path, model_to_json(model, provenance).dump(2) + "\n");
}

namespace {
// A JSON array of exactly `n` finite numbers.
std::vector<double> numbers(const core::JsonObject& obj, std::string_view key, std::size_t n) {
  const auto& a = obj.array(key);
  if (n != 0 && a.size() != n) obj.fail(key, fmt::format("must have {} numbers, got {}", n, a.size()));
  std::vector<double> out;
  for (const auto& v : a) {
    if (!v.is_number()) obj.fail(key, "must contain only numbers, got " + v.dump());
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
      if (!v.is_number()) obj.fail(key, "must contain only numbers, got " + v.dump());
      m(r, c) = v.get<double>();
    }
  }
  return m;
}

std::unique_ptr<Model> grid_model_from(const core::JsonObject& root, const std::string& method) {
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
    const core::JsonObject n(nodes_json[k], root.context() + ".nodes[" + std::to_string(k) + "]");
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

std::unique_ptr<Model> physical_model_from(const core::JsonObject& root) {
  const double l = root.positive("link_length_mm") * 1e-3;
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
      if (!d[k][m].is_number()) root.fail("D_um_per_N", "must contain only numbers, got " + d[k][m].dump());
      c[m] = d[k][m].get<double>() * 1e-6;
    }
    coefficients.push_back(c);
  }
  const int order = static_cast<int>(order_value);
  const std::size_t expected = order == 0 ? 1 : order == 1 ? 3 : 6;
  if (coefficients.size() != expected) {
    root.fail("D_um_per_N", fmt::format("order {} needs {} entries, got {}", order, expected, coefficients.size()));
  }
  return std::make_unique<PhysicalModel>(l, GridBounds{b[0] * 1e-3, b[1] * 1e-3, b[2] * 1e-3, b[3] * 1e-3}, order,
                                         std::move(coefficients),
                                         root.has("stats") ? root.raw()["stats"] : nlohmann::json::object());
}
}  // namespace

LoadedModel model_from_json(const nlohmann::json& document, const std::string& label) {
  const core::JsonObject root(document, label);
  if (root.string("format") != kModelFormat) root.fail("format", std::string("must be \"") + kModelFormat + "\"");
  if (root.number("version") != kModelFormatVersion) {
    root.fail("version", fmt::format("this stiffpath reads version {}", kModelFormatVersion));
  }
  const std::string method = root.string("method");
  LoadedModel out;
  if (method == "bilinear" || method == "symmetric") {
    out.model = grid_model_from(root, method);
  } else if (method == "physical") {
    out.model = physical_model_from(root);
  } else {
    root.fail("method", "'" + method + "' is not one of bilinear, symmetric, physical");
  }
  try {
    out.model->set_outside_policy(parse_outside_policy(root.string("outside_policy")));
    out.model->set_zero_force(parse_zero_force(root.string("zero_force")));
  } catch (const Error& e) {
    throw Error(label + ": " + e.what());
  }
  const core::JsonObject prov = root.object("provenance");
  out.provenance = {prov.string("source"), prov.string("sha256"), prov.string("mechanism"),
                    parse_force_convention(prov.string("force_convention"))};
  return out;
}

LoadedModel load_model_file(const std::string& path) { return model_from_json(core::read_json_file(path), path); }

}  // namespace stiffpath::compliance
