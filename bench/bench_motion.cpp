// Benchmarks of the motion module: profile solves per case, sampling, planning 100 000-line programs and its share of `run`.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <unistd.h>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cam_program.hpp"
#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/motion/profile.hpp"
#include "stiffpath/motion/speed_change.hpp"
#include "stiffpath/motion/slowdown.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace {
using namespace stiffpath::motion;
namespace compensation = stiffpath::compensation;
namespace compliance = stiffpath::compliance;
namespace kinematics = stiffpath::kinematics;
namespace job = stiffpath::job;

// The solver's cases, each benchmarked on its own inputs (rest-to-rest and moving ends apart).
enum class ProfileCase { cruise, both_trapezoids, two_triangles, triangle_trapezoid };

ProfileCase case_of(const ProfileInput& in, const Profile& p) {
  if (p.peak_velocity_m_s >= in.max_velocity_m_s) return ProfileCase::cruise;
  const bool up_plateau = p.phase_s[1] > 0.0, down_plateau = p.phase_s[5] > 0.0;
  if (up_plateau && down_plateau) return ProfileCase::both_trapezoids;
  return up_plateau || down_plateau ? ProfileCase::triangle_trapezoid : ProfileCase::two_triangles;
}

// 1024 feasible random inputs of one case at 2 m/s, 5 g, 5 g / 5 ms: end speeds uniform in [0, 2]
// m/s (or both 0), lengths 1e-7 … 1 m (log-uniform) beyond the least distance.
std::vector<ProfileInput> profile_inputs(ProfileCase wanted, bool rest_to_rest) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ProfileInput> inputs;
  while (inputs.size() < 1024) {
    ProfileInput in{0.0, 0.0, 0.0, 2.0, 49.03325, 9806.65};
    if (!rest_to_rest) in.start_velocity_m_s = 2.0 * unit(rng), in.end_velocity_m_s = 2.0 * unit(rng);
    const double least = speed_change(in.start_velocity_m_s, in.end_velocity_m_s, 49.03325, 9806.65).distance_m;
    in.length_m = least + std::pow(10.0, -7.0 + 7.0 * unit(rng));
    Profile p;
    if (solve_profile(in, p) == ProfileStatus::ok && case_of(in, p) == wanted) inputs.push_back(in);
  }
  return inputs;
}

void BM_SolveProfile(benchmark::State& state) {
  const auto inputs = profile_inputs(static_cast<ProfileCase>(state.range(0)), state.range(1) != 0);
  Profile profile;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(solve_profile(inputs[i++ & 1023], profile));
    benchmark::ClobberMemory();
  }
}
// First argument: 0 cruise at the limit; 1 no cruise, both halves at the acceleration limit
// (quadratic); 2 no cruise, neither half at it (quartic in the duration); 3 no cruise, one half
// at it (quartic in the ramp time; impossible from rest to rest). Second: 1 = rest to rest.
BENCHMARK(BM_SolveProfile)
    ->ArgNames({"case", "rest"})
    ->Args({0, 1})->Args({0, 0})->Args({1, 1})->Args({1, 0})->Args({2, 1})->Args({2, 0})->Args({3, 0});

void BM_ReachableSpeed(benchmark::State& state) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> lengths(1024), speeds(1024);
  for (std::size_t k = 0; k < 1024; ++k) lengths[k] = 1e-4 + 0.1 * unit(rng), speeds[k] = 2.0 * unit(rng);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1023;
    benchmark::DoNotOptimize(reachable_speed(lengths[k], speeds[k], 49.03325, 9806.65));
  }
}
BENCHMARK(BM_ReachableSpeed);

// A CAM-like program: blocks of a circle flattened to 0.2 mm chords under G64, a slot with
// tangent arcs, and hatch lines with G0 jumps, repeated until it has `lines` lines.
std::string long_program(int lines) {
  std::string g = "G21 G90 G17 G94\nG64 P0.01\nM4 S800\n";
  int n = 3, block = 0;
  while (n < lines) {
    const double cx = 200.0 + 44.0 * ((block * 7) % 10) / 10.0, cy = -60.0 + 120.0 * ((block * 3) % 10) / 10.0;
    const double r = 5.0 + (block % 5);
    const int chords = static_cast<int>(2 * std::numbers::pi * r / 0.2);
    g += fmt::format("G0 X{:.4f} Y{:.4f}\nG1 F9000\n", cx + r, cy);
    for (int k = 1; k <= chords; ++k) {
      const double t = 2 * std::numbers::pi * k / chords;
      g += fmt::format("X{:.4f} Y{:.4f}\n", cx + r * std::cos(t), cy + r * std::sin(t));
    }
    g += fmt::format("G0 X{:.4f} Y{:.4f}\nG1 X{:.4f} F6000\nG3 X{:.4f} Y{:.4f} I0 J2\nG1 X{:.4f}\nG3 X{:.4f} Y{:.4f} I0 J-2\n",
                     cx - 4, cy - 2, cx + 4, cx + 4, cy + 2, cx - 4, cx - 4, cy - 2);
    for (int k = 0; k < 20; ++k) g += fmt::format("G0 X{:.4f} Y{:.4f}\nG1 X{:.4f} F30000\n", cx - 5, cy + 0.3 * k, cx + 5);
    n += chords + 2 + 5 + 40;
    ++block;
  }
  return g + "M5\nM2\n";
}

void BM_PlanProgram100kLines(benchmark::State& state) {
  const std::string program = long_program(100000);
  std::size_t segments = 0, window = 0, evaluations = 0;
  for (auto _ : state) {
    std::istringstream in(program);
    GcodeReader reader(in, "long.gcode");
    CornerBlender blender(reader, JunctionRules{}.corner_angle_rad);
    Planner planner(blender, MotionLimits{});
    segments = 0;
    while (auto s = planner.next()) ++segments;
    window = planner.statistics().peak_window;
    evaluations = planner.statistics().entry_evaluations;
  }
  state.counters["segments"] = static_cast<double>(segments);
  state.counters["peak_window"] = static_cast<double>(window);
  state.counters["entry_evaluations_per_segment"] = static_cast<double>(evaluations) / static_cast<double>(segments);
  state.counters["ns_per_segment"] =
      benchmark::Counter(static_cast<double>(segments), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PlanProgram100kLines)->Unit(benchmark::kMillisecond);

void BM_PlanAndSample100kLines(benchmark::State& state) {
  const std::string program = long_program(100000);
  std::uint64_t samples = 0;
  for (auto _ : state) {
    std::istringstream in(program);
    TrajectoryStream stream(in, "long.gcode");
    while (auto s = stream.next()) benchmark::DoNotOptimize(s->position_m);
    samples = stream.samples();
  }
  state.counters["samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_PlanAndSample100kLines)->Unit(benchmark::kMillisecond);

void BM_SampleAt2kHz(benchmark::State& state) {
  std::istringstream in(long_program(5000));
  const Trajectory trajectory = plan_gcode(in, "job.gcode");
  std::uint64_t samples = 0;
  for (auto _ : state) {
    TrajectoryCursor cursor(trajectory);
    Sampler sampler(cursor);
    while (auto s = sampler.next()) benchmark::DoNotOptimize(s->acceleration_m_s2);
    samples += sampler.count();
  }
  state.counters["ns_per_sample"] =
      benchmark::Counter(static_cast<double>(samples), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_SampleAt2kHz)->Unit(benchmark::kMillisecond);

void BM_EvaluateAtRandomTime(benchmark::State& state) {
  std::istringstream in(long_program(5000));
  const Trajectory trajectory = plan_gcode(in, "job.gcode");
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(0.0, trajectory.duration_s());
  std::vector<double> times(1024);
  for (auto& t : times) t = unit(rng);
  std::size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(trajectory.evaluate(times[i++ & 1023]));
}
BENCHMARK(BM_EvaluateAtRandomTime);

// Planning's share of `run` on a CAM-like program of 100 000 chords (cam_program.hpp), measured in
// one process on the same text: 0 reading and blending it (the path stages), 1 also planning it
// (look-ahead, runs, profiles), 2 also sampling it at 2 kHz; and the whole `run` job with CSV or
// binary output (process CPU time: the job runs on two threads). The planner's share is
// (stage 1 − stage 0) / run. `join`: runs join on release; `fit`: the chords are fitted (--chords fit).
enum class CamStage { path, plan, sample };

void BM_CamProgram(benchmark::State& state) {
  const std::string program = stiffpath::bench::cam_program(100000);
  const auto stage = static_cast<CamStage>(state.range(0));
  PlannerOptions options;
  options.join_runs = state.range(1) != 0;
  std::size_t segments = 0, runs = 0, evaluations = 0, joined = 0;
  PlanOptions plan;
  plan.planner.junction.fit_chords = state.range(2) != 0;
  for (auto _ : state) {
    std::istringstream in(program);
    GcodeReader reader(in, "cam.gcode");
    LineMerger merger(reader);
    const auto blender_owner = make_blender(merger, plan);  // the path stages of a plan
    CornerBlender& blender = *blender_owner;
    segments = 0;
    if (stage == CamStage::path) {
      while (auto s = blender.next()) ++segments;
      continue;
    }
    Planner planner(blender, MotionLimits{}, options);
    if (stage == CamStage::plan) {
      while (auto s = planner.next()) ++segments;
    } else {
      Sampler sampler(planner);
      while (auto s = sampler.next()) benchmark::DoNotOptimize(s->position_m);
      segments = planner.statistics().segments;
    }
    runs = planner.statistics().runs;
    evaluations = planner.statistics().entry_evaluations;
    joined = planner.statistics().joined_runs;
  }
  state.counters["joined_runs"] = static_cast<double>(joined);
  state.counters["segments"] = static_cast<double>(segments);
  state.counters["runs"] = static_cast<double>(runs);
  state.counters["entry_evaluations"] = static_cast<double>(evaluations);
  state.counters["ns_per_segment"] =
      benchmark::Counter(static_cast<double>(segments), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
// join 0: each run keeps its own profile (PlannerOptions::join_runs = false), to price the joining.
BENCHMARK(BM_CamProgram)
    ->ArgNames({"stage", "join", "fit"})
    ->Args({0, 1, 0})
    ->Args({1, 0, 0})
    ->Args({1, 1, 0})
    ->Args({2, 1, 0})
    ->Args({0, 1, 1})
    ->Args({1, 1, 1})
    ->Unit(benchmark::kMillisecond);

void BM_CamRunJob(benchmark::State& state, job::OutputFormat format) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto program = dir / fmt::format("stiffpath_bench_cam_{}.gcode", ::getpid());
  const auto out = dir / fmt::format("stiffpath_bench_cam_{}.out", ::getpid());
  std::ofstream(program) << stiffpath::bench::cam_program(100000);
  const auto spec = kinematics::load_robot("oc-gu");
  const compensation::Compensator comp(spec, std::shared_ptr<const compliance::Model>(
                                                 compliance::load_model("thesis-oc").model.release()));
  for (auto _ : state) {
    TrajectoryStream stream(program);
    auto writer = job::make_joint_writer(format, out.string(), 2000.0, {spec.name, spec.geometry_hash()});
    benchmark::DoNotOptimize(job::run_job(stream, comp, writer.get(), program.string(), 2000.0).samples);
    writer.reset();
    state.PauseTiming();  // deleting the file (waiting for the disk to take its pages) is not part of the job
    std::filesystem::remove(out);
    state.ResumeTiming();
  }
  std::filesystem::remove(program);
}
BENCHMARK_CAPTURE(BM_CamRunJob, csv, job::OutputFormat::csv)->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_CamRunJob, binary, job::OutputFormat::binary)->MeasureProcessCPUTime()->Unit(benchmark::kMillisecond);

// CAM-style programs, each in the manner of one family of generators (the real programs are
// not ours to copy): what the plan takes against the time at the programmed feeds.
struct StyledProgram {
  const char* name;
  std::string text;
};

std::string f2(double v) { return fmt::format("{:.2f}", v); }

// LaserWeb: a circle (R 10 mm) and a diagonal flattened at 0.01 mm and written with two decimals, F10000.
std::string laserweb_staircase() {
  std::string g = "; LaserWeb-style\nG21\nG90\nG0 X232.13 Y0.00\nM3 S1000\nG1 F10000\n";
  std::string last;
  const int n = static_cast<int>(2 * std::numbers::pi * 10 / 0.01);
  for (int k = 1; k <= n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    const std::string p = "G1 X" + f2(222.132 + 10 * std::cos(a)) + " Y" + f2(10 * std::sin(a)) + "\n";
    if (p != last) g += p;
    last = p;
  }
  g += "M5\nG0 X200.00 Y-20.00\nM3 S1000\n";
  for (int k = 1; k <= 4000; ++k) {
    const std::string p = "G1 X" + f2(200 + 40.0 * k / 4000) + " Y" + f2(-20 + 20.0 * k / 4000) + "\n";
    if (p != last) g += p;
    last = p;
  }
  return g + "M5\nM2\n";
}

// The fine chords: a 500-chord spiral in inches under G64 P0.001, F400 (in/min).
std::string inch_spiral() {
  std::string g = "G20 G90\nG64 P0.001\nG0 X8.7453 Y0.0000\nM3 S1000\nG1 F400\n";
  for (int k = 1; k <= 500; ++k) {
    const double t = 6 * std::numbers::pi * k / 500, r = 0.1 + 0.6 * k / 500;
    g += fmt::format("X{:.4f} Y{:.4f}\n", 8.7453 + r * std::cos(t) - 0.1, r * std::sin(t));
  }
  return g + "M5\nM2\n";
}

// pcb2gcode: 0.5 mm pads outlined by 0.1 mm chords at F600 under G64 P0.01, and the traces between.
std::string pcb_pads() {
  std::string g = "G94\nG21\nG90\nG64 P0.01\nM3 S1000\n";
  for (int p = 0; p < 40; ++p) {
    const double cx = 200 + 5.0 * (p % 8), cy = -10 + 5.0 * (p / 8);
    g += fmt::format("G00 X{:.5f} Y{:.5f}\nG01 F600\n", cx + 0.5, cy);
    for (int k = 1; k <= 32; ++k) {
      const double a = 2 * std::numbers::pi * k / 32;
      g += fmt::format("G01 X{:.5f} Y{:.5f}\n", cx + 0.5 * std::cos(a), cy + 0.5 * std::sin(a));
    }
    g += fmt::format("G01 X{:.5f} Y{:.5f}\n", cx + 4.5, cy);
  }
  return g + "M5\nM2\n";
}

// LightBurn (GRBL): outlines with sharp corners (squares, hexagons, a zigzag of text-like strokes), no
// mode named, F6000.
std::string lightburn_outlines() {
  std::string g = "G00 G17 G40 G21 G54\nG90\nM4\n";
  for (int k = 0; k < 30; ++k) {
    const double cx = 190 + 8.0 * (k % 8), cy = -30 + 12.0 * (k / 8);
    const int sides = 3 + k % 4;
    g += fmt::format("G0 X{:.3f}Y{:.3f}\n", cx + 3, cy);
    for (int s = 1; s <= sides; ++s) {
      const double a = 2 * std::numbers::pi * s / sides;
      g += fmt::format("G1 X{:.3f}Y{:.3f}S800F6000\n", cx + 3 * std::cos(a), cy + 3 * std::sin(a));
    }
  }
  g += "G0 X190Y30\n";
  for (int k = 1; k <= 60; ++k) g += fmt::format("G1 X{:.3f}Y{:.3f}S800\n", 190.0 + k, 30.0 + (k % 2 ? 4 : 0));
  return g + "M5\nM2\n";
}

// Fusion: lines with tangent arcs (rounded rectangles), no mode named, F1200-3000, Z words.
std::string fusion_profiles() {
  std::string g = "G90 G94 G17 G91.1\nG21\nT1 M6\nM3 S1000\n";
  for (int k = 0; k < 20; ++k) {
    const double x = 190 + 15.0 * (k % 4), y = -40 + 16.0 * (k / 4), r = 2 + k % 3;
    g += fmt::format("G0 X{:.3f} Y{:.3f}\nG1 Z0. F1000.\n", x + r, y);
    g += fmt::format("G1 X{:.3f} F{}\n", x + 10 - r, 1200 + 300 * (k % 7));
    g += fmt::format("G3 X{:.3f} Y{:.3f} I0. J{:.3f}\n", x + 10, y + r, r);
    g += fmt::format("G1 Y{:.3f}\n", y + 8 - r);
    g += fmt::format("G3 X{:.3f} Y{:.3f} I{:.3f} J0.\n", x + 10 - r, y + 8, -r);
    g += fmt::format("G1 X{:.3f}\n", x + r);
    g += fmt::format("G3 X{:.3f} Y{:.3f} I0. J{:.3f}\n", x, y + 8 - r, -r);
    g += fmt::format("G1 Y{:.3f}\n", y + r);
    g += fmt::format("G3 X{:.3f} Y{:.3f} I{:.3f} J0.\nG0 Z5.\n", x + r, y, r);
  }
  return g + "M5\nM30\n";
}

// LightBurn fill: a hatch of 0.1 mm line spacing over 20 x 10 mm, F6000, the returns with the laser off.
std::string hatch_fill() {
  std::string g = "G21\nG90\nM4\nG0 X202 Y-5\n";
  for (int k = 0; k < 100; ++k) {
    const double y = -5 + 0.1 * k;
    g += fmt::format("G1 X{} Y{:.2f} S600 F6000\nG1 Y{:.2f} S0\n", k % 2 ? 202 : 222, y, y + 0.1);
  }
  return g + "M5\nM2\n";
}

std::vector<StyledProgram> styled_programs() {
  std::ifstream gear(std::string(STIFFPATH_SOURCE_DIR) + "/examples/gear_outline.gcode");
  std::string gear_text((std::istreambuf_iterator<char>(gear)), {});
  return {{"laserweb_staircase", laserweb_staircase()}, {"inch_spiral_p0.001", inch_spiral()},
          {"pcb2gcode_pads", pcb_pads()},                {"lightburn_outlines", lightburn_outlines()},
          {"fusion_profiles", fusion_profiles()},        {"lightburn_hatch", hatch_fill()},
          {"gear_outline", gear_text},                   {"cam_contours_20k", stiffpath::bench::cam_program(20000)}};
}

// Planned time ÷ time at the programmed feeds for each styled program (the counter `ratio`), with
// the library's defaults (5 g, 5 ms ramps, 2 m/s); `chords`: 0 blend, 1 auto (the default: fit the
// merged staircases), 2 fit. The time measured is the planning (no sampling).
void BM_CamFeedRatio(benchmark::State& state) {
  const StyledProgram program = styled_programs().at(static_cast<std::size_t>(state.range(0)));
  state.SetLabel(program.name);
  PlanOptions options;
  options.planner.junction.fit_chords = state.range(1) == 2;
  options.planner.junction.fit_merged_chords = state.range(1) != 0;
  double planned = 0.0, programmed = 0.0;
  for (auto _ : state) {
    std::istringstream in(program.text);
    GcodeReader reader(in, "styled.gcode", options.gcode);
    FeedClock clock(reader, options.limits);
    LineMerger merger(clock);
    const auto blender = make_blender(merger, options);
    Planner planner(*blender, options.limits, options.planner);
    SlowdownTap tap(planner, clock, options.limits);
    while (auto s = tap.next()) benchmark::DoNotOptimize(s->duration_s);
    planned = tap.report().planned_s();
    programmed = tap.report().programmed_s();
  }
  state.counters["planned_s"] = planned;
  state.counters["programmed_s"] = programmed;
  state.counters["ratio"] = planned / programmed;
}
BENCHMARK(BM_CamFeedRatio)->ArgNames({"program", "chords"})->ArgsProduct({{0, 1, 2, 3, 4, 5, 6, 7}, {0, 1, 2}})->Unit(benchmark::kMillisecond);

}  // namespace

// `bench_motion --write-cam-program FILE` writes the CAM-like program of the benchmarks above, for
// whole-command runs (stiffpath plan FILE against stiffpath run FILE -o out.csv); otherwise the
// benchmarks run as usual.
int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--write-cam-program") {
    std::ofstream out(argv[2]);
    out << stiffpath::bench::cam_program(100000);
    return out ? 0 : 1;
  }
  if (argc == 3 && std::string(argv[1]) == "--write-styled-programs") {  // DIR: each as DIR/NAME.gcode
    for (const auto& p : styled_programs()) std::ofstream(std::filesystem::path(argv[2]) / (std::string(p.name) + ".gcode")) << p.text;
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
