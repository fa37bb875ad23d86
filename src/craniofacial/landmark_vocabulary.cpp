#include "craniofacial/landmark_vocabulary.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "core/error.hpp"
#include "core/job.hpp"

namespace forensim {
namespace {

constexpr const char* k_ttable = "T-Table (Hona and Stephan 2024; definitions after Caple and Stephan 2016)";
constexpr const char* k_rhine =
    "Rhine's tissue-depth sites (Rhine and Campbell 1980; Rhine and Moore 1984; Taylor 2001)";
constexpr const char* k_craniometric = "craniometric point (head frame, nose and mouth rules)";

struct PairSpec {
  const char* bone;
  const char* bone_name;
  const char* bone_definition;
  const char* skin;
  const char* skin_name;
  const char* skin_definition;
  Laterality laterality;
  std::vector<std::string> bone_aliases;
  std::vector<std::string> skin_aliases;
};

void add_pair(std::vector<LandmarkSite>& sites, const PairSpec& p, const char* origin) {
  sites.push_back(
      {p.bone, p.bone_name, p.bone_definition, LandmarkSurface::bone, p.laterality, p.skin, p.bone_aliases, origin});
  sites.push_back(
      {p.skin, p.skin_name, p.skin_definition, LandmarkSurface::skin, p.laterality, p.bone, p.skin_aliases, origin});
}

std::vector<LandmarkSite> built_in_sites() {
  using L = Laterality;
  std::vector<LandmarkSite> s;
  // The 2023 T-Table, midline sites (bone -> skin).
  const std::vector<PairSpec> ttable = {
      {"op",
       "opisthocranion",
       "most posterior point of the cranium in the midsagittal plane",
       "op'",
       "soft-tissue opisthocranion",
       "skin point over opisthocranion along the depth direction",
       L::midline,
       {},
       {}},
      {"v",
       "vertex",
       "highest point of the cranial vault in the midsagittal plane",
       "v'",
       "soft-tissue vertex",
       "skin point over vertex along the depth direction",
       L::midline,
       {},
       {}},
      {"g",
       "glabella",
       "most anterior midline point of the frontal bone between the brow ridges",
       "g'",
       "soft-tissue glabella",
       "most prominent midline point of the skin between the eyebrows",
       L::midline,
       {},
       {}},
      {"n",
       "nasion",
       "intersection of the nasofrontal suture with the midsagittal plane",
       "se'",
       "sellion",
       "deepest midline point of the soft-tissue nasal bridge, over nasion",
       L::midline,
       {},
       {"soft-tissue nasion"}},
      {"mn",
       "mid-nasal",
       "midpoint between nasion and rhinion on the nasal bones",
       "mn'",
       "soft-tissue mid-nasal",
       "skin point of the nasal dorsum over mid-nasal",
       L::midline,
       {"midnasal"},
       {}},
      {"rhi",
       "rhinion",
       "end point of the internasal suture (lower end of the nasal bones)",
       "rhi'",
       "soft-tissue rhinion",
       "skin point of the nasal dorsum over rhinion",
       L::midline,
       {"end of nasals"},
       {}},
      {"ss",
       "subspinale",
       "deepest midline point below the anterior nasal spine (orthodontic point A)",
       "sn'",
       "subnasale",
       "midline junction of the columella with the upper lip",
       L::midline,
       {"point a", "a point"},
       {}},
      {"mp",
       "mid-philtrum",
       "midpoint between subspinale and prosthion on the maxilla",
       "mp'",
       "soft-tissue mid-philtrum",
       "midpoint of the philtrum of the upper lip",
       L::midline,
       {"midphiltrum"},
       {}},
      {"pr",
       "prosthion",
       "alveolar point between the upper central incisors (most anterior point of the maxillary "
       "alveolar process)",
       "ls'",
       "labrale superius",
       "midline point of the upper lip's vermilion border",
       L::midline,
       {"supradentale", "upper lip margin"},
       {"labiale superius"}},
      {"id",
       "infradentale",
       "alveolar point between the lower central incisors",
       "li'",
       "labrale inferius",
       "midline point of the lower lip's vermilion border",
       L::midline,
       {"lower lip margin"},
       {"labiale inferius"}},
      {"sm",
       "supramentale",
       "deepest midline point of the mandibular alveolar concavity (orthodontic point B)",
       "sm'",
       "soft-tissue supramentale",
       "deepest midline point of the mentolabial sulcus",
       L::midline,
       {"point b", "b point", "chin-lip fold"},
       {}},
      {"pg",
       "pogonion",
       "most anterior point of the chin on the mandibular symphysis",
       "pg'",
       "soft-tissue pogonion",
       "most anterior point of the soft-tissue chin",
       L::midline,
       {"mental eminence"},
       {}},
      {"gn",
       "gnathion",
       "midway between pogonion and menton on the symphysis outline",
       "gn'",
       "soft-tissue gnathion",
       "skin point of the chin over gnathion",
       L::midline,
       {},
       {}},
      {"me",
       "menton",
       "most inferior point of the mandibular symphysis",
       "me'",
       "soft-tissue menton",
       "lowest point of the soft-tissue chin",
       L::midline,
       {"beneath chin"},
       {}},
      // Bilateral sites.
      {"mso",
       "mid-supraorbital",
       "superior orbital rim on the line bisecting the orbit",
       "mso'",
       "soft-tissue mid-supraorbital",
       "skin point of the brow over mid-supraorbital",
       L::bilateral,
       {"midsupraorbital"},
       {}},
      {"mio",
       "mid-infraorbital",
       "inferior orbital rim on the line bisecting the orbit",
       "mio'",
       "soft-tissue mid-infraorbital",
       "skin point below the eye over mid-infraorbital",
       L::bilateral,
       {"midinfraorbital"},
       {}},
      {"ac",
       "alar curvature point (bone)",
       "point on the maxilla about 5 mm lateral to the alare of the nasal "
       "aperture",
       "ac'",
       "alar curvature",
       "deepest point of the alar crease where the nasal wing meets the cheek",
       L::bilateral,
       {},
       {"alar curvature point"}},
      {"go",
       "gonion",
       "most lateral point of the mandibular angle",
       "go'",
       "soft-tissue gonion",
       "skin point of the jaw angle over gonion",
       L::bilateral,
       {},
       {}},
      {"zy",
       "zygion",
       "most lateral point of the zygomatic arch",
       "zy'",
       "soft-tissue zygion",
       "most lateral skin point over the zygomatic arch",
       L::bilateral,
       {},
       {}},
      {"sC",
       "supra-canine",
       "point on the maxillary alveolar bone over the root eminence of the upper canine",
       "sC'",
       "soft-tissue supra-canine",
       "skin point of the upper lip and cheek over supra-canine",
       L::bilateral,
       {"supracanine"},
       {}},
      {"iC",
       "infra-canine",
       "point on the mandibular alveolar bone over the root eminence of the lower canine",
       "iC'",
       "soft-tissue infra-canine",
       "skin point of the lower lip and chin over infra-canine",
       L::bilateral,
       {"infracanine"},
       {}},
      {"ecm2",
       "ectomolare 2 (maxilla)",
       "buccal alveolar margin of the maxilla at the second molar; the T-Table "
       "measures supra-M2 from it",
       "sM2'",
       "soft-tissue supra-M2",
       "cheek skin point over the upper second molar",
       L::bilateral,
       {"maxillary ectomolare 2", "supra m2 bone"},
       {"supra-M2 skin"}},
      {"ecm2i",
       "ectomolare 2 (mandible)",
       "buccal alveolar margin of the mandible at the second molar; the T-Table "
       "writes it ecm2 as well and measures infra-M2 from it; forensim keeps the two jaws' points apart so each "
       "skin point has its own bone point",
       "iM2'",
       "soft-tissue infra-M2",
       "cheek skin point over the lower second molar",
       L::bilateral,
       {"mandibular ectomolare 2", "sub m2 bone"},
       {"infra-M2 skin"}},
      {"mr",
       "mid-ramus",
       "midpoint of the mandibular ramus",
       "mr'",
       "soft-tissue mid-ramus",
       "skin point of the cheek over mid-ramus",
       L::bilateral,
       {"midramus"},
       {}},
      {"mmb",
       "mid-mandibular border",
       "middle of the lower border of the mandibular body",
       "mmb'",
       "soft-tissue mid-mandibular border",
       "skin point below the jaw over mid-mandibular border",
       L::bilateral,
       {"mid mandibular border"},
       {}},
  };
  for (const PairSpec& p : ttable) add_pair(s, p, k_ttable);
  // Rhine's sites that have no T-Table counterpart.
  const std::vector<PairSpec> rhine = {
      {"sg",
       "supraglabella",
       "midline point of the frontal bone above glabella",
       "sg'",
       "soft-tissue supraglabella",
       "skin point of the forehead over supraglabella",
       L::midline,
       {},
       {}},
      {"fe",
       "frontal eminence",
       "most prominent point of the frontal eminence (frontal boss)",
       "fe'",
       "soft-tissue frontal eminence",
       "skin point of the forehead over the frontal eminence",
       L::bilateral,
       {},
       {}},
      {"im",
       "inferior malar",
       "lower part of the zygomatic (malar) bone below the orbit",
       "im'",
       "soft-tissue inferior malar",
       "skin point of the cheek over inferior malar",
       L::bilateral,
       {},
       {}},
      {"lo",
       "lateral orbit",
       "point on the zygomatic bone just lateral to the lateral orbital margin",
       "lo'",
       "soft-tissue lateral orbit",
       "skin point beside the eye over lateral orbit",
       L::bilateral,
       {},
       {}},
      {"sgl",
       "supraglenoid",
       "point above and in front of the external acoustic meatus, over the root of the "
       "zygomatic arch",
       "sgl'",
       "soft-tissue supraglenoid",
       "skin point in front of the ear over supraglenoid",
       L::bilateral,
       {},
       {}},
      {"ol",
       "occlusal line",
       "point on the mandibular ramus at the level of the occlusal plane (over the masseter)",
       "ol'",
       "soft-tissue occlusal line",
       "cheek skin point over the masseter at the occlusal line",
       L::bilateral,
       {"mid-masseter"},
       {}},
  };
  for (const PairSpec& p : rhine) add_pair(s, p, k_rhine);
  // Craniometric points without a tissue-depth pair.
  s.push_back({"po",
               "porion",
               "highest point of the upper margin of the external acoustic meatus (head frame)",
               LandmarkSurface::bone,
               L::bilateral,
               "",
               {},
               k_craniometric});
  s.push_back({"or",
               "orbitale",
               "lowest point of the inferior margin of the orbit (head frame)",
               LandmarkSurface::bone,
               L::bilateral,
               "",
               {},
               k_craniometric});
  s.push_back({"ans",
               "anterior nasal spine",
               "tip of the anterior nasal spine (acanthion); Krogman's nose-tip rule "
               "extends the spine",
               LandmarkSurface::bone,
               L::midline,
               "",
               {"acanthion"},
               k_craniometric});
  s.push_back({"al",
               "alare (bone)",
               "most lateral point of the margin of the nasal aperture; the nose rule puts the "
               "skin alare 5 mm lateral to it",
               LandmarkSurface::bone,
               L::bilateral,
               "",
               {"nasal aperture width point"},
               k_craniometric});
  s.push_back({"prn'",
               "pronasale",
               "most anterior point of the nose tip",
               LandmarkSurface::skin,
               L::midline,
               "",
               {"nose tip"},
               k_craniometric});
  s.push_back({"al'",
               "alare",
               "most lateral point of the nasal wing",
               LandmarkSurface::skin,
               L::bilateral,
               "",
               {"nose wing"},
               k_craniometric});
  s.push_back({"ch'",
               "cheilion",
               "corner of the mouth",
               LandmarkSurface::skin,
               L::bilateral,
               "",
               {"mouth corner"},
               k_craniometric});
  s.push_back({"sto'",
               "stomion",
               "midline point of the lip parting line",
               LandmarkSurface::skin,
               L::midline,
               "",
               {"stomion"},
               k_craniometric});
  return s;
}

std::vector<RhineSite> built_in_rhine_sites() {
  using L = Laterality;
  const char* same = "same site as the T-Table's";
  return {
      {"supraglabella", L::midline, "sg", false, "Rhine only", {}},
      {"glabella", L::midline, "g", true, same, {}},
      {"nasion", L::midline, "n", true, same, {}},
      {"end of nasals", L::midline, "rhi", true, same, {"rhinion"}},
      {"mid-philtrum", L::midline, "mp", true, same, {}},
      {"upper lip margin", L::midline, "pr", true, same, {"supradentale", "prosthion"}},
      {"lower lip margin", L::midline, "id", true, same, {"infradentale"}},
      {"chin-lip fold", L::midline, "sm", true, same, {"supramentale"}},
      {"mental eminence", L::midline, "pg", true, same, {"pogonion"}},
      {"beneath chin", L::midline, "me", true, same, {"menton"}},
      {"frontal eminence", L::bilateral, "fe", false, "Rhine only", {}},
      {"supraorbital",
       L::bilateral,
       "mso",
       false,
       "nearest T-Table site: Rhine measures above the orbit centred on its upper margin, the T-Table on the rim "
       "where the line bisecting the orbit crosses it",
       {}},
      {"suborbital",
       L::bilateral,
       "mio",
       false,
       "nearest T-Table site: Rhine measures below the orbit centred on its lower margin, the T-Table on the rim "
       "where the line bisecting the orbit crosses it",
       {}},
      {"inferior malar", L::bilateral, "im", false, "Rhine only", {}},
      {"lateral orbit", L::bilateral, "lo", false, "Rhine only", {}},
      {"zygomatic arch, midway",
       L::bilateral,
       "zy",
       false,
       "nearest T-Table site: Rhine measures midway along the arch, the T-Table at its most lateral point (zygion)",
       {"zygomatic arch", "zygion"}},
      {"supraglenoid", L::bilateral, "sgl", false, "Rhine only", {}},
      {"gonion", L::bilateral, "go", true, same, {}},
      {"supra M2", L::bilateral, "ecm2", true, "same site as the T-Table's ecm2 -> sM2'", {}},
      {"occlusal line", L::bilateral, "ol", false, "Rhine only", {"mid-masseter"}},
      {"sub M2", L::bilateral, "ecm2i", true, "same site as the T-Table's ecm2 -> iM2' (mandibular ecm2)", {}},
  };
}

struct SideSplit {
  std::string base;
  Side side = Side::none;
};

/// Splits a normalised name into its site part and a side word at either end ("zy l", "left zy", "zy' (r)").
std::vector<SideSplit> side_splits(const std::string& key) {
  std::vector<SideSplit> out;
  out.push_back({key, Side::none});
  const auto side_of = [](const std::string& word) {
    if (word == "l" || word == "left" || word == "(l)" || word == "(left)") return Side::left;
    if (word == "r" || word == "right" || word == "(r)" || word == "(right)") return Side::right;
    return Side::none;
  };
  const std::size_t last_space = key.rfind(' ');
  if (last_space != std::string::npos) {
    std::string word = key.substr(last_space + 1);
    std::string base = key.substr(0, last_space);
    if (!word.empty() && word.back() == '\'' && word.size() > 1) {  // "zy_L'" written with the prime last
      word.pop_back();
      base += '\'';
    }
    const Side side = side_of(word);
    if (side != Side::none && !base.empty()) out.push_back({base, side});
  }
  const std::size_t first_space = key.find(' ');
  if (first_space != std::string::npos) {
    const Side side = side_of(key.substr(0, first_space));
    if (side != Side::none) out.push_back({key.substr(first_space + 1), side});
  }
  return out;
}

}  // namespace

std::string normalise_landmark_name(std::string_view name) {
  std::string out;
  bool pending_space = false;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    // Typographic primes and apostrophes in UTF-8: U+2019, U+2018 (E2 80 99/98), U+2032 (E2 80 B2), U+00B4 (C2 B4).
    if (c == 0xE2 && i + 2 < name.size() && static_cast<unsigned char>(name[i + 1]) == 0x80) {
      const unsigned char d = static_cast<unsigned char>(name[i + 2]);
      if (d == 0x99 || d == 0x98 || d == 0xB2) {
        if (pending_space && !out.empty()) out += ' ';
        pending_space = false;
        out += '\'';
        i += 2;
        continue;
      }
    }
    if (c == 0xC2 && i + 1 < name.size() && static_cast<unsigned char>(name[i + 1]) == 0xB4) {
      if (pending_space && !out.empty()) out += ' ';
      pending_space = false;
      out += '\'';
      ++i;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '_' || c == '-' || c == '.' || c == ',') {
      pending_space = true;
      continue;
    }
    if (pending_space && !out.empty()) out += ' ';
    pending_space = false;
    out += (c == '`') ? '\'' : static_cast<char>(std::tolower(c));
  }
  return out;
}

std::string side_word(Side side) {
  switch (side) {
    case Side::left:
      return "left";
    case Side::right:
      return "right";
    case Side::none:
      break;
  }
  return "";
}

std::string side_suffix(Side side) {
  switch (side) {
    case Side::left:
      return "_L";
    case Side::right:
      return "_R";
    case Side::none:
      break;
  }
  return "";
}

LandmarkVocabulary::LandmarkVocabulary(std::vector<LandmarkSite> sites, std::vector<RhineSite> rhine_sites)
    : m_sites(std::move(sites)), m_rhine(std::move(rhine_sites)) {
  const auto add_key = [this](const std::string& name, std::size_t site) {
    const std::string key = normalise_landmark_name(name);
    if (key.empty()) throw std::logic_error("landmark vocabulary: empty name for site " + m_sites[site].abbreviation);
    m_keys.emplace_back(key, site);
  };
  for (std::size_t i = 0; i < m_sites.size(); ++i) {
    const LandmarkSite& s = m_sites[i];
    add_key(s.abbreviation, i);
    add_key(s.full_name, i);
    for (const std::string& alias : s.aliases) add_key(alias, i);
    m_suggestions.push_back(s.abbreviation);
    m_suggestions.push_back(s.full_name);
  }
  const auto site_index = [this](const std::string& abbreviation) -> std::optional<std::size_t> {
    for (std::size_t i = 0; i < m_sites.size(); ++i) {
      if (m_sites[i].abbreviation == abbreviation) return i;
    }
    return std::nullopt;
  };
  for (const RhineSite& r : m_rhine) {
    const auto bone = site_index(r.bone_site);
    if (!bone || m_sites[*bone].surface != LandmarkSurface::bone || m_sites[*bone].laterality != r.laterality) {
      throw std::logic_error("landmark vocabulary: Rhine site '" + r.name + "' maps to no bone site of its laterality");
    }
    add_key(r.name, *bone);
    for (const std::string& alias : r.aliases) add_key(alias, *bone);
    m_suggestions.push_back(r.name);
  }
  for (std::size_t i = 0; i < m_sites.size(); ++i) {
    const LandmarkSite& s = m_sites[i];
    if (s.pair.empty()) continue;
    const auto other = site_index(s.pair);
    if (!other || m_sites[*other].pair != s.abbreviation || m_sites[*other].surface == s.surface ||
        m_sites[*other].laterality != s.laterality) {
      throw std::logic_error("landmark vocabulary: pair of '" + s.abbreviation + "' is not mutual");
    }
  }
  std::sort(m_keys.begin(), m_keys.end());
  m_keys.erase(std::unique(m_keys.begin(), m_keys.end()), m_keys.end());
  for (std::size_t i = 1; i < m_keys.size(); ++i) {
    if (m_keys[i].first == m_keys[i - 1].first) {
      throw std::logic_error("landmark vocabulary: name '" + m_keys[i].first + "' names two sites ('" +
                             m_sites[m_keys[i - 1].second].abbreviation + "' and '" +
                             m_sites[m_keys[i].second].abbreviation + "')");
    }
  }
}

const LandmarkVocabulary& LandmarkVocabulary::built_in() {
  static const LandmarkVocabulary vocabulary(built_in_sites(), built_in_rhine_sites());
  return vocabulary;
}

std::optional<std::size_t> LandmarkVocabulary::find_site(std::string_view name) const {
  const std::string key = normalise_landmark_name(name);
  const auto it = std::lower_bound(m_keys.begin(), m_keys.end(), key,
                                   [](const auto& entry, const std::string& k) { return entry.first < k; });
  if (it == m_keys.end() || it->first != key) return std::nullopt;
  return it->second;
}

std::optional<LandmarkRef> LandmarkVocabulary::find(std::string_view name) const {
  for (const SideSplit& split : side_splits(normalise_landmark_name(name))) {
    const auto site = find_site(split.base);
    if (!site) continue;
    if (split.side != Side::none && m_sites[*site].laterality == Laterality::midline) return std::nullopt;
    return LandmarkRef{*site, split.side};
  }
  return std::nullopt;
}

std::string LandmarkVocabulary::suggest(std::string_view name) const {
  const std::string key = normalise_landmark_name(name);
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(2, key.size() / 3) + 1;
  const auto consider = [&](const std::string& candidate_name, const std::string& shown) {
    const std::size_t d = edit_distance(key, normalise_landmark_name(candidate_name));
    if (d < best_distance) {
      best_distance = d;
      best = shown;
    }
  };
  for (const std::string& s : m_suggestions) consider(s, s);
  for (const LandmarkSite& s : m_sites) {
    if (s.laterality != Laterality::bilateral) continue;
    for (Side side : {Side::left, Side::right})
      consider(s.abbreviation + side_suffix(side), s.abbreviation + side_suffix(side));
  }
  return best;
}

LandmarkRef LandmarkVocabulary::resolve(std::string_view name, const std::string& source,
                                        const std::string& location) const {
  const std::string shown(name);
  for (const SideSplit& split : side_splits(normalise_landmark_name(name))) {
    const auto site = find_site(split.base);
    if (!site) continue;
    const LandmarkSite& s = m_sites[*site];
    if (s.laterality == Laterality::midline && split.side != Side::none) {
      throw InputError(source, location,
                       "landmark '" + shown + "': " + s.abbreviation + " (" + s.full_name +
                           ") is a midline site and has no side; write '" + s.abbreviation + "'");
    }
    if (s.laterality == Laterality::bilateral && split.side == Side::none) {
      throw InputError(source, location,
                       "landmark '" + shown + "': " + s.abbreviation + " (" + s.full_name +
                           ") is bilateral; name the side: '" + s.abbreviation + "_L' or '" + s.abbreviation + "_R'");
    }
    return LandmarkRef{*site, split.side};
  }
  std::string problem = "unknown landmark '" + shown + "'";
  const std::string hint = suggest(name);
  if (!hint.empty()) problem += " (did you mean '" + hint + "'?)";
  throw InputError(source, location, problem);
}

std::size_t LandmarkVocabulary::resolve_site(std::string_view name, const std::string& source,
                                             const std::string& location) const {
  const std::string shown(name);
  if (const auto site = find_site(name)) return *site;
  if (const auto ref = find(name); ref && ref->side != Side::none) {
    const LandmarkSite& s = m_sites[ref->site];
    throw InputError(source, location,
                     "'" + shown + "' names one side; a site is written without a side ('" + s.abbreviation +
                         "', used for both sides)");
  }
  std::string problem = "unknown landmark site '" + shown + "'";
  const std::string hint = suggest(name);
  if (!hint.empty()) problem += " (did you mean '" + hint + "'?)";
  throw InputError(source, location, problem);
}

std::string LandmarkVocabulary::name(const LandmarkRef& ref) const {
  return m_sites.at(ref.site).abbreviation + side_suffix(ref.side);
}

std::string LandmarkVocabulary::canonical_name(std::string_view name, const std::string& source,
                                               const std::string& location) const {
  return this->name(resolve(name, source, location));
}

std::optional<LandmarkRef> LandmarkVocabulary::paired(const LandmarkRef& ref) const {
  const LandmarkSite& s = m_sites.at(ref.site);
  if (s.pair.empty()) return std::nullopt;
  for (std::size_t i = 0; i < m_sites.size(); ++i) {
    if (m_sites[i].abbreviation == s.pair) return LandmarkRef{i, ref.side};
  }
  return std::nullopt;
}

std::vector<std::string> LandmarkVocabulary::landmark_names(LandmarkSurface surface) const {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < m_sites.size(); ++i) {
    const LandmarkSite& s = m_sites[i];
    if (s.surface != surface) continue;
    if (s.laterality == Laterality::midline) {
      out.push_back(s.abbreviation);
    } else {
      out.push_back(s.abbreviation + side_suffix(Side::left));
      out.push_back(s.abbreviation + side_suffix(Side::right));
    }
  }
  return out;
}

}  // namespace forensim
