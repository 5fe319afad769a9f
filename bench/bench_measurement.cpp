// Benchmarks of the measurement module: campaign processing (readings/s), file load + processing, data checks.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <unistd.h>

#include "stiffpath/measurement/campaign.hpp"
#include "stiffpath/measurement/data_check.hpp"
#include "stiffpath/measurement/process_campaign.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"

namespace {
using namespace stiffpath::measurement;

Campaign make_campaign(int readings_per_step) {
  VirtualCampaignOptions o;
  o.readings_per_step = readings_per_step;
  return simulate_campaign(linear_truth(load_displacement_table(stiffpath::measurement::thesis_dataset()).filter("OC")), o);
}

// In-memory processing (eq. 2.3, tilt, averaging); items = CMM readings (rows of the raw file).
void BM_ProcessCampaign(benchmark::State& state) {
  const Campaign c = make_campaign(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(process_campaign(c, {}));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(c.readings.size()));
}
BENCHMARK(BM_ProcessCampaign)->Arg(1)->Arg(10)->Unit(benchmark::kMicrosecond);

// What `stiffpath measure` does: parse and validate the CSV, then process.
void BM_LoadAndProcessCampaign(benchmark::State& state) {
  const Campaign c = make_campaign(static_cast<int>(state.range(0)));
  const auto path = std::filesystem::temp_directory_path() / ("bench_campaign_" + std::to_string(::getpid()) + ".csv");
  save_campaign(c, path.string());
  for (auto _ : state) benchmark::DoNotOptimize(process_campaign(load_campaign(path.string()), {}));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(c.readings.size()));
  std::filesystem::remove(path);
}
BENCHMARK(BM_LoadAndProcessCampaign)->Arg(1)->Arg(10)->Unit(benchmark::kMicrosecond);

// `stiffpath data check thesis` without the printing; items = table rows.
void BM_DataCheckThesis(benchmark::State& state) {
  const DisplacementTable t = load_displacement_table(stiffpath::measurement::thesis_dataset());
  for (auto _ : state) benchmark::DoNotOptimize(check_displacements(t));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(t.rows.size()));
}
BENCHMARK(BM_DataCheckThesis)->Unit(benchmark::kMicrosecond);

}  // namespace
