#pragma once
/// The names forensim gives to craniofacial landmarks: every site of the 2023 T-Table (Hona and Stephan 2024,
/// names and definitions after Caple and Stephan 2016), the sites of Rhine's tissue-depth tables that the
/// T-Table lacks, and the few craniometric points the head frame and the nose and mouth rules need (porion,
/// orbitale, anterior nasal spine, alare, pronasale, cheilion, stomion).
///
/// Conventions (reference: shared/reference/tissue-depth.md, section 1):
/// - a bone (skull) landmark is written plain ("n"), a skin landmark primed ("se'");
/// - a tissue-depth measurement goes from a bone landmark to its paired skin landmark (n -> se', ss -> sn',
///   pr -> ls', zy -> zy'); the pairing is part of the vocabulary;
/// - bilateral sites carry a side suffix in a landmark's name: "zy_L", "zy'_R" (the subject's left and right);
///   midline sites have none. Tissue-depth tables give one value per site for both sides.
///
/// Lookup accepts the canonical name and aliases: full names ("nasion", "left zygion"), other spellings of
/// the side ("zy-l", "zy L", "zy (left)"), typographic primes (’ ′) and any letter case where that is
/// unambiguous. Unknown names raise InputError with the nearest known name.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace forensim {

/// Which surface a landmark lies on.
enum class LandmarkSurface { bone, skin };
/// Whether a site lies on the midsagittal plane or occurs on both sides.
enum class Laterality { midline, bilateral };
/// The side of a concrete landmark: none for midline sites, left or right (the subject's) for bilateral ones.
enum class Side { none, left, right };

/// One landmark site (a bilateral site stands for both its sides).
struct LandmarkSite {
  std::string abbreviation;  ///< canonical short name: "n", "se'", "zy", "zy'", "ecm2"
  std::string full_name;     ///< "nasion", "sellion", "zygion"
  std::string definition;    ///< where the point lies, after the source named in `origin`
  LandmarkSurface surface = LandmarkSurface::bone;
  Laterality laterality = Laterality::midline;
  std::string pair;                  ///< abbreviation of the paired site on the other surface, or empty
  std::vector<std::string> aliases;  ///< other names accepted by lookup
  std::string origin;                ///< where the site comes from ("T-Table", "Rhine", "craniometric")
};

/// One of the 21 sites of Rhine's tissue-depth tables (Rhine and Campbell 1980; Rhine and Moore 1984; as
/// listed in Taylor 2001), with the vocabulary's bone site that it is measured from.
struct RhineSite {
  std::string name;  ///< Rhine's name: "supraglabella", "end of nasals", "supra M2"
  Laterality laterality = Laterality::midline;
  std::string bone_site;        ///< abbreviation of the vocabulary's bone site for it ("g", "rhi", "ecm2")
  bool same_as_ttable = false;  ///< true when `bone_site` is a T-Table site that Rhine's site coincides with
  std::string note;             ///< how Rhine's site relates to `bone_site` (exact, nearest T-Table site, Rhine only)
  std::vector<std::string> aliases;  ///< other names for the site in Rhine's tables ("supradentale")
};

/// A concrete landmark: a site and a side.
struct LandmarkRef {
  std::size_t site = 0;  ///< index into LandmarkVocabulary::sites()
  Side side = Side::none;
  bool operator==(const LandmarkRef& other) const { return site == other.site && side == other.side; }
};

/// The landmark vocabulary. The built-in one is immutable and shared; it is the one the rest of the module
/// uses. Sites are ordered: bone sites of the T-Table (midline, then bilateral) with their skin sites, then
/// Rhine-only sites, then craniometric points.
class LandmarkVocabulary {
 public:
  /// A vocabulary over `sites` and `rhine_sites`. Throws std::logic_error when two sites or aliases collide
  /// after normalisation, a pair is not mutual or a Rhine site names no bone site (a programming error).
  LandmarkVocabulary(std::vector<LandmarkSite> sites, std::vector<RhineSite> rhine_sites);

  /// The built-in vocabulary.
  static const LandmarkVocabulary& built_in();

  const std::vector<LandmarkSite>& sites() const { return m_sites; }
  const std::vector<RhineSite>& rhine_sites() const { return m_rhine; }
  const LandmarkSite& site(const LandmarkRef& ref) const { return m_sites.at(ref.site); }

  /// Index of the site named `name` (abbreviation, full name, alias or Rhine name; no side), or nullopt.
  std::optional<std::size_t> find_site(std::string_view name) const;
  /// The landmark named `name`, with its side parsed from the name, or nullopt when the site is unknown or
  /// the side does not fit it (a side on a midline site). A bilateral site without a side gives Side::none.
  std::optional<LandmarkRef> find(std::string_view name) const;

  /// A concrete landmark for a name: the site must be known and a bilateral site needs a side. Throws
  /// InputError(source, location, ...) naming the problem, with "did you mean" for unknown names.
  LandmarkRef resolve(std::string_view name, const std::string& source, const std::string& location) const;
  /// A site (no side) for a name, as tissue-depth tables name them. Throws InputError for unknown names (with
  /// "did you mean") and for names with a side.
  std::size_t resolve_site(std::string_view name, const std::string& source, const std::string& location) const;

  /// Canonical name of a landmark: "n", "se'", "zy_L", "zy'_R".
  std::string name(const LandmarkRef& ref) const;
  /// Canonical name of `name` (any accepted spelling). Throws as resolve().
  std::string canonical_name(std::string_view name, const std::string& source, const std::string& location) const;

  /// The landmark on the other surface that `ref` pairs with (n -> se', zy'_L -> zy_L), or nullopt.
  std::optional<LandmarkRef> paired(const LandmarkRef& ref) const;
  /// Every concrete landmark name on `surface` (bilateral sites give _L and _R), in vocabulary order.
  std::vector<std::string> landmark_names(LandmarkSurface surface) const;
  /// The nearest known name to `name` by edit distance (for messages), or empty when nothing is close.
  std::string suggest(std::string_view name) const;

 private:
  std::vector<LandmarkSite> m_sites;
  std::vector<RhineSite> m_rhine;
  std::vector<std::pair<std::string, std::size_t>> m_keys;  // normalised name -> site, sorted by name
  std::vector<std::string> m_suggestions;                   // canonical names and full names, for "did you mean"
};

/// Lower-cased `name` with typographic primes turned into ', runs of spaces, '_', '-' and '.' turned into
/// one space and the ends trimmed: the key that lookup compares.
std::string normalise_landmark_name(std::string_view name);

/// "left", "right" or "" for Side::none; and the suffix a canonical name carries: "_L", "_R", "".
std::string side_word(Side side);
std::string side_suffix(Side side);

}  // namespace forensim
