// Robustness figure: the worst path accuracy over seeds for each off-nominal condition, per compensation.
#include "stiffpath/report/robustness_plots.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {

std::vector<std::string> write_robustness_figures(const std::filesystem::path& dir,
                                                  const std::vector<simulation::RobustnessRow>& rows, Style style) {
  std::vector<std::string> motions, variants, conditions;
  const auto add = [](std::vector<std::string>& v, const std::string& s) {
    if (std::find(v.begin(), v.end(), s) == v.end()) v.push_back(s);
  };
  const auto label = [](const simulation::RobustnessRow& r) {
    return r.factor == "nominal" ? std::string("nominal") : fmt::format("{}={:g}", r.factor, r.value);
  };
  for (const auto& r : rows) {
    add(motions, r.motion);
    add(variants, std::string(core::enum_name(r.variant)));
    add(conditions, label(r));
  }
  std::vector<std::string> rendered;
  for (const auto& motion : motions) {
    const std::string data = "robustness_" + motion + ".tsv";
    std::string text = "# condition";
    for (const auto& v : variants) text += "\tworst_ATp_um_" + v;
    text += "\n";
    for (const auto& c : conditions) {
      text += "\"" + c + "\"";
      for (const auto& v : variants) {
        const auto it = std::find_if(rows.begin(), rows.end(), [&](const auto& r) {
          return r.motion == motion && core::enum_name(r.variant) == v && label(r) == c;
        });
        text += it == rows.end() ? "\tNaN" : fmt::format("\t{:.2f}", it->worst_path_accuracy_m * 1e6);
      }
      text += "\n";
    }
    core::write_file_atomically(dir / data, text);
    std::string plots;
    for (std::size_t k = 0; k < variants.size(); ++k) {
      if (!plots.empty()) plots += ", \\\n  ";
      plots += fmt::format("{} using 0:{}{} with linespoints pt 7 title {}", quote(data), k + 2,
                           k == 0 ? ":xtic(1)" : "", quote(variants[k]));
    }
    Figure figure;
    figure.name = "robustness_" + motion;
    figure.style = style;
    figure.commands = fmt::format(
        "set title {}\nset ylabel 'worst AT_p over seeds (µm)'\nset grid\nset key outside right\n"
        "set xtics rotate by -40\nset logscale y\nset bmargin 8\nplot {}\n",
        quote("simulated: " + motion + ", compensation off nominal (one factor at a time)"), plots);
    render(dir, figure);
    rendered.push_back(figure.name);
  }
  return rendered;
}

}  // namespace stiffpath::report
