// forensim bench wound: the abrasion's five key positions, all of them, and one timeline sample at 2048^2
// and 4096^2 beside the thesis's Table 4.2 (Linnenbank 2015: 2 / 105 / 126 / 175 / 97 ms per phase and
// 943 ms for all phases on a GTX 780) and the project's goals on 2 cores (all phases < 94 ms, one timeline
// sample < 5 ms at 2048^2). The wound is drawn on a flat patch of skin covering the whole texture (256 mm
// at 8 texels/mm for 2048^2, the thesis's density as read in wound/abrasion.hpp): two overlapping ellipses
// about 60 x 35 mm, as bench/bench_wound.cpp's "full" case.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "bench_registry.hpp"
#include "core/parallel.hpp"
#include "texture/polygon_fill.hpp"
#include "wound/abrasion.hpp"
#include "wound/flat_canvas.hpp"
#include "wound/timeline.hpp"

namespace forensim::cli {
namespace {

std::shared_ptr<WoundCanvas> bench_canvas(int size) {
  Image upper, lower;
  default_skin_maps(size, size, 5, upper, lower);
  std::vector<std::vector<Vec2>> rings(2);
  for (int k = 0; k < 64; ++k) {
    const double a = 2.0 * M_PI * k / 64.0;
    rings[0].push_back(Vec2(size * (0.42 + 0.12 * std::cos(a)), size * (0.5 + 0.07 * std::sin(a))));
    rings[1].push_back(Vec2(size * (0.58 + 0.06 * std::cos(a)), size * (0.45 + 0.1 * std::sin(a))));
  }
  return std::make_shared<WoundCanvas>(
      make_flat_canvas(fill_polygon(size, size, rings), size / 256.0, upper, lower, 5));
}

// CPU seconds of all the process's threads so far (the machine may be shared: this is the work done, which
// wall times on a loaded machine overstate).
double process_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// time_repeated, with the mean CPU time per run (all threads) written into `cpu_text`.
BenchTiming timed(int repetitions, const std::function<void()>& fn, std::string& cpu_text) {
  const double c0 = process_cpu_s();
  const BenchTiming t = time_repeated(repetitions, fn);
  char buf[64];
  std::snprintf(buf, sizeof buf, "cpu %.1f ms/run", 1e3 * (process_cpu_s() - c0) / std::max(repetitions, 1));
  cpu_text = buf;
  return t;
}

std::string kilo_texels(std::size_t n) {
  return std::to_string((n + 500) / 1000) + "k texels written";
}

std::vector<BenchRow> run_wound(const BenchOptions& options) {
  const std::vector<int> sizes = options.size == "small" ? std::vector<int>{1024} : std::vector<int>{2048, 4096};
  const char* phases[] = {"vasoconstriction", "vasodilation", "scab_forming", "scab", "maturation"};
  const double paper_ms[] = {2, 105, 126, 175, 97};
  const std::string ref = "Table 4.2, GTX 780";
  const std::string threads = std::to_string(thread_count()) + " threads";
  std::vector<BenchRow> rows;
  for (const int size : sizes) {
    const bool paper_size = size == 2048;
    const auto canvas = bench_canvas(size);
    std::string at = " ";  // appended, not inserted (GCC 12 misreports inserting into a string as an overlap)
    at += std::to_string(size);
    at += "^2";
    std::vector<std::shared_ptr<const KeyPosition>> keys;
    std::vector<TiledMapSet> outputs(5);  // reused between runs, as render targets
    for (int p = 0; p < 5; ++p) {
      keys.push_back(make_abrasion_key(phases[p]));
      keys.back()->render_into(*canvas, 0.5, outputs[static_cast<std::size_t>(p)]);  // warm-up
    }
    for (int p = 0; p < 5; ++p) {
      std::string cpu;
      const auto t = timed(
          options.repetitions,
          [&] { keys[static_cast<std::size_t>(p)]->render_into(*canvas, 0.5, outputs[static_cast<std::size_t>(p)]); },
          cpu);
      rows.push_back({std::string(phases[p]) + at, t.median_s, t.min_s, paper_size ? paper_ms[p] * 1e-3 : -1.0, ref,
                      -1.0,
                      kilo_texels(outputs[static_cast<std::size_t>(p)].stored_texels()) + ", " + threads + ", " + cpu});
    }
    std::string cpu;
    const auto all = timed(
        options.repetitions,
        [&] {
          for (int p = 0; p < 5; ++p)
            keys[static_cast<std::size_t>(p)]->render_into(*canvas, 0.5, outputs[static_cast<std::size_t>(p)]);
        },
        cpu);
    std::size_t written = 0;
    for (const auto& o : outputs) written += o.stored_texels();
    rows.push_back({std::string("all phases") + at, all.median_s, all.min_s, paper_size ? 0.943 : -1.0, ref,
                    paper_size ? 0.094 : -1.0, kilo_texels(written) + ", " + threads + ", " + cpu});
    // One timeline sample between vasoconstriction and vasodilation, copy-on-write into a tiled set, then
    // the same written out as full-texture float maps (the form saved to files).
    Timeline timeline(default_abrasion_timeline());
    timeline.render(canvas);
    TiledMapSet sample;
    double time_s = 400.0;
    timeline.sample(time_s, sample);
    const auto s = timed(
        std::max(options.repetitions, 20),
        [&] {
          time_s = time_s < 800.0 ? time_s + 1.0 : 400.0;
          timeline.sample(time_s, sample);
        },
        cpu);
    rows.push_back(
        {std::string("timeline sample") + at, s.median_s, s.min_s, -1.0, "", paper_size ? 0.005 : -1.0,
         std::to_string((sample.stored_texels() + 500) / 1000) + "k texels blended, " + threads + ", " + cpu});
    MapSet full = skin_map_set(canvas->upper_skin, 0.25f);
    const auto f = time_repeated(options.repetitions, [&] { timeline.sample_full(time_s, full); });
    rows.push_back({std::string("timeline sample as full float maps") + at, f.median_s, f.min_s, -1.0, "", -1.0,
                    std::string("export form, ") + threads});
  }
  return rows;
}

const RegisterBench wound_bench{{"wound",
                                 "Abrasion key positions (per phase, all) and a timeline sample at 2048^2 and "
                                 "4096^2 beside the thesis's Table 4.2",
                                 run_wound}};

}  // namespace
}  // namespace forensim::cli
