// Fitting models by method name, the built-in thesis models, and dispatch between files and built-ins.
#include "stiffpath/compliance/model_factory.hpp"

#include <filesystem>
#include <fmt/format.h>

#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/model_file.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/core/embedded.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/sha256.hpp"

namespace stiffpath::compliance {

std::vector<std::string> method_names() { return {"bilinear", "symmetric", "physical", "physical-0", "physical-2"}; }

namespace {
std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::string data_hash(const std::string& source) {
  if (source == "thesis") {
    const auto text = core::find_embedded("thesis/displacements.csv");
    return text ? core::sha256_hex(*text) : "";
  }
  // A table built in memory has no file to hash.
  return std::filesystem::is_regular_file(source) ? core::sha256_file_hex(source) : "";
}
}  // namespace

LoadedModel fit_model(const measurement::DisplacementTable& table, const std::string& mechanism,
                      const std::string& method, ForceConvention convention, double link_length_m) {
  const auto rows = table.filter(mechanism);
  if (rows.rows.empty()) {
    throw Error(SourceLocation{table.source}, fmt::format("no rows for mechanism '{}' (the table has: {})", mechanism,
                                                          join(table.mechanisms())));
  }
  const auto points = group_by_point(rows, convention);
  LoadedModel out;
  out.provenance = {table.source, data_hash(table.source), mechanism, convention};
  if (method == "bilinear") {
    out.model = make_bilinear_model(fit_points(rows, convention), table.source);
  } else if (method == "symmetric") {
    out.model = make_symmetric_model(points, table.source);
  } else if (method == "physical" || method == "physical-0" || method == "physical-2") {
    const int order = method == "physical" ? 1 : method.back() - '0';
    out.model = fit_physical_model(points, link_length_m, order, table.source);
  } else {
    throw Error(fmt::format("unknown compliance method '{}' (known: {})", method, join(method_names())));
  }
  return out;
}

bool is_builtin_model(const std::string& name) { return name.rfind("thesis-", 0) == 0; }

LoadedModel load_model(const std::string& name_or_path) {
  if (!is_builtin_model(name_or_path)) return load_model_file(name_or_path);
  // thesis-<oc|sc>[-<method>]
  const std::string rest = name_or_path.substr(7);
  const std::string build = rest.substr(0, 2);
  const std::string method = rest.size() > 3 && rest[2] == '-' ? rest.substr(3) : "bilinear";
  if ((build != "oc" && build != "sc") || (rest.size() > 2 && rest[2] != '-')) {
    throw Error(fmt::format("unknown built-in model '{}' (use thesis-oc or thesis-sc, optionally with -<method>: {})",
                            name_or_path, join(method_names())));
  }
  return fit_model(measurement::load_displacement_table("thesis"), build == "oc" ? "OC" : "SC", method);
}

}  // namespace stiffpath::compliance
