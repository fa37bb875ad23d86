// forensim bench: times each system's hot steps on paper-sized inputs beside the paper's figures (targets
// register themselves from bench_<system>.cpp through bench_registry.hpp).

#include <nlohmann/json.hpp>

#include <cstdio>
#include <memory>
#include <string>

#include "bench_registry.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace forensim::cli {
namespace {

std::string time_text(double s) {
  char buf[32];
  if (s < 0.0) return "-";
  if (s < 1e-3) {
    std::snprintf(buf, sizeof buf, "%.1f us", s * 1e6);
  } else if (s < 1.0) {
    std::snprintf(buf, sizeof buf, "%.1f ms", s * 1e3);
  } else {
    std::snprintf(buf, sizeof buf, "%.2f s", s);
  }
  return buf;
}

nlohmann::json run_target(const BenchTarget& target, const BenchOptions& options) {
  std::printf("== forensim bench %s (%s; median of %d)\n", target.name.c_str(), options.size.c_str(),
              options.repetitions);
  std::printf("%-44s %10s %10s %10s %9s %10s  %s\n", "step", "median", "min", "paper", "speed-up", "goal", "note");
  std::fflush(stdout);
  nlohmann::json rows = nlohmann::json::array();
  for (const BenchRow& row : target.run(options)) {
    char speedup[32] = "-";
    if (row.paper_s > 0.0 && row.median_s > 0.0)
      std::snprintf(speedup, sizeof speedup, "%.1fx", row.paper_s / row.median_s);
    std::printf("%-44s %10s %10s %10s %9s %10s  %s\n", row.name.c_str(), time_text(row.median_s).c_str(),
                time_text(row.min_s).c_str(), time_text(row.paper_s).c_str(), speedup, time_text(row.goal_s).c_str(),
                row.note.c_str());
    std::fflush(stdout);
    nlohmann::json j = {{"step", row.name}, {"median_s", row.median_s}, {"min_s", row.min_s}, {"note", row.note}};
    if (row.paper_s > 0.0) j["paper_s"] = row.paper_s, j["paper_ref"] = row.paper_ref;
    if (row.goal_s > 0.0) j["goal_s"] = row.goal_s;
    rows.push_back(j);
  }
  const double peak_mib = static_cast<double>(peak_rss_bytes()) / (1024.0 * 1024.0);
  std::printf("peak memory (resident, process so far): %.0f MiB\n", peak_mib);
  return {{"target", target.name}, {"size", options.size}, {"rows", rows}, {"peak_rss_mib", peak_mib}};
}

const RegisterCommand bench_command{
    "bench", [](CLI::App& app) {
      auto* sub = app.add_subcommand(
          "bench", "Time each system's steps on paper-sized inputs beside the papers' figures, with peak memory");
      auto system = std::make_shared<std::string>();
      auto options = std::make_shared<BenchOptions>();
      auto json_path = std::make_shared<std::string>();
      std::string names;
      for (const BenchTarget& t : bench_registry()) names += (names.empty() ? "" : ", ") + t.name;
      sub->add_option("system", *system, "What to time: " + names + " or all")->required();
      sub->add_option("--repeat", options->repetitions, "Timed runs per step (median reported)")
          ->check(CLI::Range(1, 1000));
      sub->add_option("--size", options->size, "Input size preset: small, paper or fine")
          ->check(CLI::IsMember({"small", "paper", "fine"}));
      sub->add_option("--json", *json_path, "Also write the figures to this JSON file");
      return [=]() {
        nlohmann::json out = nlohmann::json::array();
        bool found = false;
        for (const BenchTarget& t : bench_registry()) {
          if (*system != "all" && *system != t.name) continue;
          found = true;
          out.push_back(run_target(t, *options));
        }
        if (!found)
          throw Error("forensim bench: unknown system '" + *system + "' (known: " + names + ", all)", ErrorKind::usage);
        if (!json_path->empty()) write_file_atomic(*json_path, out.dump(2) + "\n");
        return 0;
      };
    }};

}  // namespace
}  // namespace forensim::cli
