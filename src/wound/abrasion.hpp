#pragma once
/// The abrasion of Linnenbank 2015 ("Real-time simulation of abrasion wound healing", MSc thesis, Utrecht
/// University, chapter 4.3): five key positions with the thesis's colours and noise parameters.
///
/// Scale: the thesis gives distances in texels of its hand texture (glow and scab gradient thickness 100,
/// erosion kernel widths 3-5 and 3-10, noise periods 2^i). Here they are millimetres on the skin:
/// texels / thesis_texels_per_mm, drawn at the canvas's texels_per_mm, and noise periods are raised by
/// log2(texels_per_mm / thesis_texels_per_mm) octaves, so the wound looks the same at any resolution.
/// The thesis does not state its texel density; 8 texels/mm (a 2048 texture over about 256 mm of hand) is
/// our reading, so the 100-texel glow is 12.5 mm wide.

#include <memory>
#include <string>
#include <vector>

#include "wound/key_position.hpp"
#include "wound/timeline.hpp"

namespace forensim {

struct AbrasionParams {
  double thesis_texels_per_mm = 8.0;  ///< texel density the thesis's pixel sizes refer to
  double glow_thickness_px = 100.0;   ///< outward red glow (chapter 4.3.2), thesis texels
  double scab_gradient_px = 100.0;    ///< inward dark red scab rim (chapter 4.3.4), thesis texels
  double scab_height_mm = 0.8;    ///< scab thickness at height noise 1 (the thesis's displacement scale is unstated)
  float skin_reflection = 0.25f;  ///< reflection of healthy skin (the thesis uses a specularity texture)
  double shrink_min = 0.4, shrink_max = 0.8;  ///< eq. 4.8's rand(0.4, 0.8)
  /// Maturation's maxOuterGradBorder: true = the thesis's half closing distance (half the diameter, right for
  /// the round convex wounds it draws); false = the deepest distance from the border inside the wound, the
  /// distance a wound of any shape must close (equal to half the diameter for a disk; much smaller for a long
  /// scrape, which the thesis's rule would leave nearly skin-coloured from the start).
  bool thesis_closing_distance = false;

  /// Thesis texels -> mm on the skin.
  double px_to_mm(double px) const { return px / thesis_texels_per_mm; }
  /// Largest distance from the wound border any abrasion key reads, mm (the canvas's reach).
  double reach_mm() const;
};

/// Thesis colours (linear RGB as printed).
namespace abrasion_colors {
inline const Vec4f wound_red(0.79f, 0.0f, 0.0f, 1.0f);      ///< vasodilation red, glow (4.3.2), WOUND_RED (4.3.5)
inline const Vec4f edge_grey(0.95f, 0.95f, 0.95f, 1.0f);    ///< scraped edge multiplier (4.3.2)
inline const Vec4f speckle_red(0.88f, 0.20f, 0.22f, 1.0f);  ///< scab-forming speckles (4.3.3)
inline const Vec4f scab_rim_red(0.5f, 0.04f, 0.03f, 1.0f);  ///< scab inward gradient (4.3.4)
inline const Vec4f scab_light(0.78f, 0.48f, 0.27f, 1.0f);   ///< lighter yellowish scab (4.3.4)
inline const Vec4f scab_dark(0.39f, 0.12f, 0.11f, 1.0f);    ///< darker scab (4.3.4)
inline const Vec4f wound_white(0.79f, 0.41f, 0.41f, 1.0f);  ///< WOUND_WHITE, maturation (4.3.5)
}  // namespace abrasion_colors

/// Chapter 4.3.1: lower skin inside the shape, upper skin outside.
class VasoconstrictionKey : public KeyPosition {
 public:
  explicit VasoconstrictionKey(AbrasionParams params = {}) : m_params(params) {}
  std::string name() const override { return "vasoconstriction"; }
  void render_into(const WoundCanvas& canvas, double local_position, TiledMapSet& out) const override;

 private:
  AbrasionParams m_params;
};

/// Chapter 4.3.2: lower skin x red inside, outward glow (red -> upper skin over 100 px), scraped edge from two
/// erosions (m in [3, 5] then [3, 10]) at 0.95 grey x upper skin, stretched noise (5 octaves, persistence
/// 0.09, bias 0.5, gain 0.43, scaled 64x along y) as the wound's reflection.
class VasodilationKey : public KeyPosition {
 public:
  explicit VasodilationKey(AbrasionParams params = {}) : m_params(params) {}
  std::string name() const override { return "vasodilation"; }
  void render_into(const WoundCanvas& canvas, double local_position, TiledMapSet& out) const override;

 private:
  AbrasionParams m_params;
};

/// Chapter 4.3.3: glow; inside, eq. 4.5 (bottom noise 5 oct, 0.85, 0.54, 0.21 blends lower and upper skin) and
/// eq. 4.6 (speckle noise 5 oct, 0.48, 0.16, 0.15 times (0.88, 0.20, 0.22) blended by its red).
class ScabFormingKey : public KeyPosition {
 public:
  explicit ScabFormingKey(AbrasionParams params = {}) : m_params(params) {}
  std::string name() const override { return "scab_forming"; }
  void render_into(const WoundCanvas& canvas, double local_position, TiledMapSet& out) const override;

 private:
  AbrasionParams m_params;
};

/// Chapter 4.3.4: height = mask noise (7 oct, 1.0, 0.44, 0.02) x noise (5 oct, 0.54, 0.3, 0.69); rim = inward
/// gradient (0.5, 0.04, 0.03) -> black over 100 px masked by noise (5 oct, 0.33, 0.60, 0.59); body =
/// Lerp(light, dark, height); colour = eq. 4.7 screen(body, rim); glow; reflection noise (10 oct, 1.0, 0.25, 0.95).
class ScabKey : public KeyPosition {
 public:
  explicit ScabKey(AbrasionParams params = {}) : m_params(params) {}
  std::string name() const override { return "scab"; }
  void render_into(const WoundCanvas& canvas, double local_position, TiledMapSet& out) const override;

 private:
  AbrasionParams m_params;
};

/// Chapter 4.3.5: re-rendered at every position p: closing distance c (Algorithm 4.3, or the deepest inside
/// distance, see AbrasionParams::thesis_closing_distance), eq. 4.8 borders outer = c/2 p, inner = outer + c/2
/// rand(0.4, 0.8) (seeded), Algorithm 4.4 inside the shape with the
/// distance to the border: skin up to outer, Lerp(skin, WOUND_RED) up to inner, then Lerp(WOUND_RED,
/// WOUND_WHITE) towards the centre. The wound area falls to zero at p = 1.
class MaturationKey : public KeyPosition {
 public:
  explicit MaturationKey(AbrasionParams params = {}) : m_params(params) {}
  std::string name() const override { return "maturation"; }
  void render_into(const WoundCanvas& canvas, double local_position, TiledMapSet& out) const override;
  bool rerenders() const override { return true; }
  /// Eq. 4.8's borders (mm) for the canvas at position p: {outer, inner}.
  std::pair<double, double> borders_mm(const WoundCanvas& canvas, double position) const;

 private:
  AbrasionParams m_params;
};

/// The key position of an abrasion phase by name: vasoconstriction, vasodilation, scab_forming, scab,
/// maturation. Throws InputError for another name.
std::shared_ptr<const KeyPosition> make_abrasion_key(const std::string& phase, const AbrasionParams& params = {});

/// The default abrasion timeline at physiological times (thesis chapter 2.1): vasoconstriction held 0-5 min,
/// vasodilation at 15 min, scab-forming held 2 h-2 d, scab held 5 d-10 d, an instant cut to maturation at
/// 10 d re-rendered to its end at 4 weeks.
std::vector<TimelineEntry> default_abrasion_timeline(const AbrasionParams& params = {});

/// Number of texels of a maturation map set still showing the wound (colour differs from the upper skin by
/// more than `tolerance` in any channel) inside the canvas shape.
std::size_t visible_wound_texels(const WoundCanvas& canvas, const MapSet& maps, float tolerance = 1e-4f);

}  // namespace forensim
