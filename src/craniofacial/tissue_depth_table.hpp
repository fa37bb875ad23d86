#pragma once
/// Facial soft-tissue depth tables: the published mean depth (and SD where given) from each bone landmark to
/// its skin landmark, for a group of people (sex, population, build). The paper scales each landmark's
/// vector to the depth "looked up automatically by the landmark's assigned name in a table" (Kahler et al.
/// 2003, section 3) and picks the slender, normal or obese table for a build (section 1.2).
///
/// Tables are CSV files (the built-in ones are data/tissue_depth/*.csv, compiled into the library):
///   '#' comment lines (the table's source; kept as provenance), then a header and one row per site and group:
///   landmark       a site of the vocabulary (bone abbreviation such as "n", a full or Rhine name such as
///                  "nasion" or "end of nasals", or the skin landmark of the pair such as "se'"); no side:
///                  one value serves both sides of a bilateral site
///   skin_landmark  optional: the pair's skin landmark, checked against the vocabulary's pairing
///   mean_mm        mean depth in mm (finite, > 0)
///   sd_mm          standard deviation in mm (finite, >= 0), or empty when the source gives none; optional column
///   sex            female, male or pooled
///   population     the population the sample comes from (free text, not empty; "pooled" when
///                  pooled over populations)
///   build          slender, normal, obese or pooled
///   source         the publication the row comes from (not empty)
/// A (sex, population, build) combination is a group; a site may appear once per group.
///
/// Build variants come from the table's own slender/normal/obese groups or from the means plus or minus k
/// standard deviations; no offset that the table does not give is ever invented.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace forensim {

/// The group a row belongs to.
struct TissueDepthGroup {
  std::string sex;         ///< "female", "male" or "pooled"
  std::string population;  ///< e.g. "pooled", "Southwestern Native American"
  std::string build;       ///< "slender", "normal", "obese" or "pooled"
  bool operator==(const TissueDepthGroup& other) const {
    return sex == other.sex && population == other.population && build == other.build;
  }
  /// "female, Southwestern Native American, normal".
  std::string describe() const;
};

/// One row of a table.
struct TissueDepthRow {
  std::string site;             ///< vocabulary abbreviation of the bone site ("n", "zy", "ecm2i")
  double mean_mm = 0.0;         ///< mean depth, mm
  std::optional<double> sd_mm;  ///< standard deviation, mm, when the source gives one
  TissueDepthGroup group;
  std::string source;  ///< publication
  int line = 0;        ///< line in the table file
};

/// A parsed table.
struct TissueDepthTable {
  std::string name;                   ///< built-in name ("ttable_2023") or the file's stem
  std::string origin;                 ///< "built-in" or the file path
  std::vector<std::string> comments;  ///< the file's '#' header lines (its source)
  std::vector<TissueDepthRow> rows;

  /// Distinct groups in order of first appearance.
  std::vector<TissueDepthGroup> groups() const;
};

/// Parses table text; `origin` names it in messages. Throws InputError(origin, "line N, field F", problem) for
/// a malformed table: unknown column or landmark (with "did you mean"), a landmark with a side or without a
/// skin pair, a skin_landmark that is not the pair's, a mean that is NaN, infinite, zero or negative, a
/// negative or non-finite SD, an unknown sex or build, empty population or source, a site given twice in one
/// group (naming both lines), or no rows.
TissueDepthTable parse_tissue_depth_table(const std::string& text, const std::string& origin, const std::string& name);
/// Reads a table file (at most 16 MiB). Throws IoError when it cannot be read, InputError as above.
TissueDepthTable load_tissue_depth_table(const std::filesystem::path& path);
/// Names of the built-in tables: "rhine_1983_sw_native_american_female_normal", "ttable_2023".
std::vector<std::string> built_in_tissue_depth_table_names();
/// The default table: "ttable_2023" (the largest and most recent pooled data).
std::string default_tissue_depth_table_name();
/// A built-in table by name. Throws InputError ("did you mean") for an unknown name.
TissueDepthTable built_in_tissue_depth_table(const std::string& name);
/// A built-in table when `name_or_path` is a built-in name, else the file at that path.
TissueDepthTable tissue_depth_table(const std::string& name_or_path);

/// Which group to use; an empty field accepts any value.
struct TissueDepthQuery {
  std::string sex;
  std::string population;
  std::string build;
};

/// One site's depth in a selection.
struct TissueDepthEntry {
  std::string site;             ///< vocabulary bone abbreviation
  double mean_mm = 0.0;         ///< depth to use, mm
  std::optional<double> sd_mm;  ///< SD of the source, mm
  std::string source;           ///< publication, and how the value was derived when not the mean
  int line = 0;                 ///< table line
};

/// The depths of one group of one table: what a reconstruction uses and records as provenance.
struct TissueDepths {
  std::string table;                      ///< table name
  TissueDepthGroup group;                 ///< the group the values come from
  std::string variant;                    ///< "mean" or how the values were derived ("mean - 1 SD")
  std::vector<std::string> notes;         ///< where the group differs from the query (pooled values used)
  std::vector<TissueDepthEntry> entries;  ///< one per site, in table order

  /// Entry for a vocabulary site abbreviation, or nullptr.
  const TissueDepthEntry* find_site(const std::string& site) const;
  /// Depth for a landmark name (any vocabulary spelling, with or without a side; a skin landmark gives its
  /// pair's depth), or nullopt when the table has no value for its site or the name is not a paired landmark.
  std::optional<double> depth_mm(const std::string& landmark) const;
  /// The names in `landmarks` (bone landmarks with a skin pair) that have no depth here, in input order.
  std::vector<std::string> missing(const std::vector<std::string>& landmarks) const;
};

/// The depths of the one group that best fits `query`. A group fits when each of its fields equals the
/// query's (or the query's is empty) or is "pooled" (a pooled value stands for any sex, population or build,
/// and a note says so); among fitting groups the one with fewest pooled stand-ins wins. Throws InputError
/// naming the table and listing its groups when none fits or two fit equally well.
TissueDepths select_tissue_depths(const TissueDepthTable& table, const TissueDepthQuery& query = {});

/// Every entry's mean moved by k standard deviations (mean + k SD). Throws InputError naming the site when an
/// entry has no SD or the result is not positive. The variant and sources record the offset.
TissueDepths offset_by_sd(const TissueDepths& depths, double k);

/// One member of an ensemble of plausible depths (for showing a reconstruction's uncertainty): each site's depth
/// drawn from the normal distribution of its mean and SD, truncated to positive depths by redrawing. Draws come
/// from RandomStream(seed, member), sites in table order, so a member is reproducible and independent of thread
/// count. The variant records seed and member. Throws InputError naming the site when an entry has no SD.
TissueDepths sample_tissue_depths(const TissueDepths& depths, std::uint64_t seed, std::uint64_t member);

/// The paper's three builds for one group.
struct BuildVariants {
  TissueDepths slender, normal, obese;
  std::string method;  ///< "table groups" or "mean -/+ k SD"

  /// The variant named "slender", "normal" or "obese". Throws InputError naming "build" for another name.
  const TissueDepths& of(const std::string& build) const;
};
/// Slender, normal and obese depths for the sex and population of `query` (its build is ignored): the table's
/// own slender, normal and obese groups when it has all three, else the selected group's mean - k SD, mean and
/// mean + k SD. Throws InputError when neither is possible (no build groups and no SDs).
BuildVariants build_variants(const TissueDepthTable& table, const TissueDepthQuery& query = {}, double k_sd = 1.0);

}  // namespace forensim
