#pragma once
/// A bruise (contusion) through the same framework as the abrasion, to show it is general: blood under
/// intact skin, so the skin colour is multiplied by a tint that follows haemoglobin degradation (red-blue
/// haemoglobin and deoxyhaemoglobin in the first day, green biliverdin from about day 5, yellow bilirubin
/// and haemosiderin from about day 7, fading by 2-3 weeks; Langlois & Gresham 1991, Hughes et al. 2004). The
/// edge is soft and the stain spreads a little as blood diffuses. No relief: the height map stays 0.

#include <memory>
#include <string>
#include <vector>

#include "wound/key_position.hpp"
#include "wound/timeline.hpp"

namespace forensim {

/// One stage of a bruise.
struct BruiseStage {
  std::string name;                ///< "fresh", "blue", "green", "yellow", "faded"
  Vec4f tint = Vec4f(1, 1, 1, 1);  ///< linear RGB multiplier of the skin at full strength
  double strength = 1.0;           ///< [0, 1]: how far the skin goes to the tint at the centre
  double spread_mm = 2.0;          ///< soft edge: the stain fades over this distance outside the shape
  double inner_soft_mm = 3.0;      ///< and reaches full strength this far inside
};

/// The stage by name: fresh (red-purple), blue (blue-purple), green, yellow, faded. InputError otherwise.
BruiseStage bruise_stage(const std::string& name);

class BruiseKey : public KeyPosition {
 public:
  explicit BruiseKey(BruiseStage stage) : m_stage(std::move(stage)) {}
  std::string name() const override { return m_stage.name; }
  /// colour = skin x Lerp(1, tint, strength w m), w = smoothstep falloff of the signed distance to the
  /// border, m = 0.75 + 0.25 mottling value noise; reflection 0.25 (intact skin); height 0.
  void render_into(const WoundCanvas& canvas, double local_position, TiledMapSet& out) const override;
  nlohmann::json describe() const override;
  const BruiseStage& stage() const { return m_stage; }

 private:
  BruiseStage m_stage;
};

/// Default bruise timeline: fresh at 0, blue at 1 d, green at 5 d, yellow at 8 d, faded at 18 d.
std::vector<TimelineEntry> default_bruise_timeline();

/// Largest distance outside the shape a bruise reads (mm), for the canvas's reach.
double bruise_reach_mm();

}  // namespace forensim
