#include "craniofacial/tissue_depth_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/job.hpp"
#include "core/random.hpp"
#include "craniofacial/csv_table.hpp"
#include "craniofacial/embedded_tables.hpp"
#include "craniofacial/landmark_vocabulary.hpp"

namespace forensim {
namespace {

constexpr std::size_t k_max_table_bytes = std::size_t{16} << 20;

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string field_location(int line, const std::string& column) {
  return "line " + std::to_string(line) + ", field " + column;
}

std::string choice(const std::string& text, const std::vector<std::string>& choices, const std::string& origin,
                   int line, const std::string& column) {
  const std::string t = lower(text);
  for (const std::string& c : choices) {
    if (t == c) return c;
  }
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "'" : ", '") + c + "'";
  throw InputError(origin, field_location(line, column), "'" + text + "' is not one of " + list);
}

/// How many fields of `group` stand in for the query through "pooled"; nullopt when the group does not fit.
std::optional<int> pooled_count(const TissueDepthGroup& group, const TissueDepthQuery& query,
                                std::vector<std::string>* notes) {
  int pooled = 0;
  const auto field = [&](const std::string& have, const std::string& want, const char* what) {
    if (want.empty() || lower(want) == lower(have)) return true;
    if (have == "pooled") {
      ++pooled;
      if (notes) {
        notes->push_back(std::string(what) + " '" + want + "' requested; the table gives pooled values (" + have + ")");
      }
      return true;
    }
    return false;
  };
  if (!field(group.sex, query.sex, "sex")) return std::nullopt;
  if (!field(group.population, query.population, "population")) return std::nullopt;
  if (!field(group.build, query.build, "build")) return std::nullopt;
  return pooled;
}

std::string groups_list(const TissueDepthTable& table) {
  std::string out;
  for (const TissueDepthGroup& g : table.groups()) out += (out.empty() ? "" : "; ") + g.describe();
  return out;
}

std::string describe_query(const TissueDepthQuery& q) {
  const auto f = [](const std::string& s) { return s.empty() ? std::string("any") : s; };
  return "sex " + f(q.sex) + ", population " + f(q.population) + ", build " + f(q.build);
}

}  // namespace

std::string TissueDepthGroup::describe() const {
  return sex + ", " + population + ", " + build;
}

std::vector<TissueDepthGroup> TissueDepthTable::groups() const {
  std::vector<TissueDepthGroup> out;
  for (const TissueDepthRow& row : rows) {
    if (std::find(out.begin(), out.end(), row.group) == out.end()) out.push_back(row.group);
  }
  return out;
}

TissueDepthTable parse_tissue_depth_table(const std::string& text, const std::string& origin, const std::string& name) {
  const CsvTable csv = parse_csv(text, origin);
  check_csv_columns(csv, {"landmark", "mean_mm", "sex", "population", "build", "source"}, {"sd_mm", "skin_landmark"});
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const std::size_t c_landmark = *csv.column("landmark");
  const std::size_t c_mean = *csv.column("mean_mm");
  const std::size_t c_sex = *csv.column("sex");
  const std::size_t c_population = *csv.column("population");
  const std::size_t c_build = *csv.column("build");
  const std::size_t c_source = *csv.column("source");
  const auto c_sd = csv.column("sd_mm");
  const auto c_skin = csv.column("skin_landmark");

  TissueDepthTable table;
  table.name = name;
  table.origin = origin;
  table.comments = csv.comments;
  for (const CsvRow& row : csv.rows) {
    const int line = row.line;
    std::size_t site = vocabulary.resolve_site(row.fields[c_landmark], origin, field_location(line, "landmark"));
    if (vocabulary.sites()[site].surface == LandmarkSurface::skin) {
      const auto bone = vocabulary.paired(LandmarkRef{site, Side::none});
      if (bone) site = bone->site;
    }
    const LandmarkSite& s = vocabulary.sites()[site];
    if (s.pair.empty()) {
      throw InputError(
          origin, field_location(line, "landmark"),
          "'" + row.fields[c_landmark] + "' (" + s.full_name + ") has no skin landmark to measure a depth to");
    }
    if (c_skin && !row.fields[*c_skin].empty()) {
      const std::size_t skin =
          vocabulary.resolve_site(row.fields[*c_skin], origin, field_location(line, "skin_landmark"));
      if (vocabulary.sites()[skin].abbreviation != s.pair) {
        throw InputError(
            origin, field_location(line, "skin_landmark"),
            "'" + row.fields[*c_skin] + "' is not the skin landmark of " + s.abbreviation + " (" + s.pair + ")");
      }
    }
    TissueDepthRow r;
    r.site = s.abbreviation;
    r.line = line;
    r.mean_mm = parse_csv_number(row.fields[c_mean], origin, line, "mean_mm");
    if (!(r.mean_mm > 0.0)) {
      throw InputError(origin, field_location(line, "mean_mm"), "depth " + row.fields[c_mean] + " mm is not positive");
    }
    if (c_sd && !row.fields[*c_sd].empty()) {
      const double sd = parse_csv_number(row.fields[*c_sd], origin, line, "sd_mm");
      if (sd < 0.0) throw InputError(origin, field_location(line, "sd_mm"), "SD " + row.fields[*c_sd] + " is negative");
      r.sd_mm = sd;
    }
    r.group.sex = choice(row.fields[c_sex], {"female", "male", "pooled"}, origin, line, "sex");
    r.group.build = choice(row.fields[c_build], {"slender", "normal", "obese", "pooled"}, origin, line, "build");
    r.group.population = row.fields[c_population];
    if (r.group.population.empty()) throw InputError(origin, field_location(line, "population"), "is empty");
    r.source = row.fields[c_source];
    if (r.source.empty()) throw InputError(origin, field_location(line, "source"), "is empty (name the publication)");
    for (const TissueDepthRow& earlier : table.rows) {
      if (earlier.site == r.site && earlier.group == r.group) {
        throw InputError(origin, field_location(line, "landmark"),
                         "site " + r.site + " is given twice for " + r.group.describe() + " (also on line " +
                             std::to_string(earlier.line) + ")");
      }
    }
    table.rows.push_back(std::move(r));
  }
  if (table.rows.empty()) throw InputError(origin, "", "tissue-depth table has no rows");
  return table;
}

TissueDepthTable load_tissue_depth_table(const std::filesystem::path& path) {
  return parse_tissue_depth_table(read_file(path, k_max_table_bytes), path.string(), path.stem().string());
}

std::vector<std::string> built_in_tissue_depth_table_names() {
  std::vector<std::string> out;
  for (const EmbeddedFile& f : embedded_tissue_depth_tables()) out.emplace_back(f.name);
  return out;
}

std::string default_tissue_depth_table_name() {
  return "ttable_2023";
}

TissueDepthTable built_in_tissue_depth_table(const std::string& name) {
  for (const EmbeddedFile& f : embedded_tissue_depth_tables()) {
    if (f.name == name) {
      TissueDepthTable table = parse_tissue_depth_table(std::string(f.text), "built-in table " + name, name);
      table.origin = "built-in";
      return table;
    }
  }
  std::string best, all;
  std::size_t best_distance = 4;
  for (const std::string& n : built_in_tissue_depth_table_names()) {
    all += (all.empty() ? "" : ", ") + n;
    const std::size_t d = edit_distance(name, n);
    if (d < best_distance) {
      best_distance = d;
      best = n;
    }
  }
  std::string problem = "no built-in tissue-depth table '" + name + "'";
  if (!best.empty()) problem += " (did you mean '" + best + "'?)";
  throw InputError("tissue-depth table", "", problem + "; built-in tables: " + all);
}

TissueDepthTable tissue_depth_table(const std::string& name_or_path) {
  for (const std::string& n : built_in_tissue_depth_table_names()) {
    if (n == name_or_path) return built_in_tissue_depth_table(n);
  }
  if (!std::filesystem::exists(name_or_path) && name_or_path.find('/') == std::string::npos &&
      name_or_path.find(".csv") == std::string::npos) {
    return built_in_tissue_depth_table(name_or_path);  // neither a file nor a built-in name: says which exist
  }
  return load_tissue_depth_table(name_or_path);
}

const TissueDepthEntry* TissueDepths::find_site(const std::string& site) const {
  for (const TissueDepthEntry& e : entries) {
    if (e.site == site) return &e;
  }
  return nullptr;
}

std::optional<double> TissueDepths::depth_mm(const std::string& landmark) const {
  const LandmarkVocabulary& vocabulary = LandmarkVocabulary::built_in();
  const auto ref = vocabulary.find(landmark);
  if (!ref) return std::nullopt;
  LandmarkRef bone = *ref;
  if (vocabulary.site(bone).surface == LandmarkSurface::skin) {
    const auto p = vocabulary.paired(bone);
    if (!p) return std::nullopt;
    bone = *p;
  }
  if (vocabulary.site(bone).pair.empty()) return std::nullopt;
  const TissueDepthEntry* e = find_site(vocabulary.site(bone).abbreviation);
  if (e == nullptr) return std::nullopt;
  return e->mean_mm;
}

std::vector<std::string> TissueDepths::missing(const std::vector<std::string>& landmarks) const {
  std::vector<std::string> out;
  for (const std::string& l : landmarks) {
    if (!depth_mm(l)) out.push_back(l);
  }
  return out;
}

TissueDepths select_tissue_depths(const TissueDepthTable& table, const TissueDepthQuery& query) {
  const std::vector<TissueDepthGroup> groups = table.groups();
  int best = -1;
  std::vector<std::size_t> best_groups;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto pooled = pooled_count(groups[g], query, nullptr);
    if (!pooled) continue;
    if (best < 0 || *pooled < best) {
      best = *pooled;
      best_groups = {g};
    } else if (*pooled == best) {
      best_groups.push_back(g);
    }
  }
  const std::string source = "tissue-depth table " + table.name;
  if (best_groups.empty()) {
    throw InputError(source, "", "no group fits " + describe_query(query) + "; the table has: " + groups_list(table));
  }
  if (best_groups.size() > 1) {
    std::string fits;
    for (std::size_t g : best_groups) fits += (fits.empty() ? "" : "; ") + groups[g].describe();
    throw InputError(source, "",
                     "several groups fit " + describe_query(query) + " (" + fits + "); name sex, population and build");
  }
  TissueDepths out;
  out.table = table.name;
  out.group = groups[best_groups.front()];
  out.variant = "mean";
  pooled_count(out.group, query, &out.notes);
  for (const TissueDepthRow& row : table.rows) {
    if (!(row.group == out.group)) continue;
    out.entries.push_back({row.site, row.mean_mm, row.sd_mm, row.source, row.line});
  }
  return out;
}

TissueDepths offset_by_sd(const TissueDepths& depths, double k) {
  if (!std::isfinite(k)) throw InputError("tissue-depth variant", "k", "number of SDs is not finite");
  TissueDepths out = depths;
  const std::string offset = k >= 0.0 ? fmt::format("mean + {} SD", k) : fmt::format("mean - {} SD", -k);
  out.variant = offset;
  for (TissueDepthEntry& e : out.entries) {
    if (!e.sd_mm) {
      throw InputError("tissue-depth table " + depths.table, "site " + e.site,
                       "has no SD, so '" + offset + "' cannot be formed (no offset is invented)");
    }
    const double value = e.mean_mm + k * *e.sd_mm;
    if (!(value > 0.0)) {
      throw InputError("tissue-depth table " + depths.table, "site " + e.site,
                       fmt::format("{} = {} + {} x {} mm is not positive", offset, e.mean_mm, k, *e.sd_mm));
    }
    e.mean_mm = value;
    e.source += " (" + offset + ")";
  }
  return out;
}

TissueDepths sample_tissue_depths(const TissueDepths& depths, std::uint64_t seed, std::uint64_t member) {
  TissueDepths out = depths;
  out.variant = fmt::format("sampled from mean and SD (seed {}, member {})", seed, member);
  RandomStream rng(seed, member);
  for (TissueDepthEntry& e : out.entries) {
    if (!e.sd_mm) {
      throw InputError("tissue-depth table " + depths.table, "site " + e.site,
                       "has no SD, so depths cannot be sampled (no spread is invented)");
    }
    double value = e.mean_mm;
    if (*e.sd_mm > 0.0) {
      // Means are several SDs above zero in published tables, so redrawing ends quickly; the cap only guards
      // against a hostile user table.
      int tries = 0;
      do {
        value = rng.normal(e.mean_mm, *e.sd_mm);
      } while (!(value > 0.0) && ++tries < 1000);
      if (!(value > 0.0)) value = e.mean_mm;
    }
    e.mean_mm = value;
    e.source += " (sampled)";
  }
  return out;
}

const TissueDepths& BuildVariants::of(const std::string& build) const {
  if (build == "slender") return slender;
  if (build == "normal") return normal;
  if (build == "obese") return obese;
  throw InputError("build", build, "is not slender, normal or obese");
}

BuildVariants build_variants(const TissueDepthTable& table, const TissueDepthQuery& query, double k_sd) {
  BuildVariants out;
  bool from_groups = true;
  TissueDepths* targets[3] = {&out.slender, &out.normal, &out.obese};
  const char* builds[3] = {"slender", "normal", "obese"};
  for (int b = 0; b < 3 && from_groups; ++b) {
    bool exact = false;
    for (const TissueDepthGroup& g : table.groups()) {
      if (g.build != builds[b]) continue;
      if (pooled_count(g, {query.sex, query.population, builds[b]}, nullptr)) exact = true;
    }
    if (!exact) {
      from_groups = false;
      break;
    }
    *targets[b] = select_tissue_depths(table, {query.sex, query.population, builds[b]});
  }
  if (from_groups) {
    out.method = "table groups";
    return out;
  }
  if (!(k_sd > 0.0) || !std::isfinite(k_sd)) {
    throw InputError("tissue-depth variant", "k", "number of SDs must be positive and finite");
  }
  out.normal = select_tissue_depths(table, {query.sex, query.population, ""});
  for (const TissueDepthEntry& e : out.normal.entries) {
    if (!e.sd_mm) {
      throw InputError("tissue-depth table " + table.name, "line " + std::to_string(e.line),
                       "has no slender/normal/obese groups and no SD for site " + e.site +
                           ", so build variants cannot be formed without invented offsets");
    }
  }
  out.slender = offset_by_sd(out.normal, -k_sd);
  out.obese = offset_by_sd(out.normal, k_sd);
  out.method = fmt::format("mean -/+ {} SD", k_sd);
  return out;
}

}  // namespace forensim
