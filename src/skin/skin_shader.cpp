#include "skin/skin_shader.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "skin/chromophores.hpp"

namespace forensim {

namespace {

const SkinShadingSettings& checked(const SkinShadingSettings& s) {
  const std::string src = "skin shading settings";
  require_input(std::isfinite(s.drying_boost) && s.drying_boost >= 0.0 && s.drying_boost <= 4.0, src, "drying_boost",
                "must be in [0, 4]");
  require_input(std::isfinite(s.oxygen_decay_hours) && s.oxygen_decay_hours > 0.0, src, "oxygen_decay_hours",
                "must be positive");
  return s;
}

Vec4f rgba(const Vec3& c) {
  return Vec4f(static_cast<float>(std::clamp(c[0], 0.0, 1.0)), static_cast<float>(std::clamp(c[1], 0.0, 1.0)),
               static_cast<float>(std::clamp(c[2], 0.0, 1.0)), 1.0f);
}

void check_sizes(const SkinLayers& layers, const LivorState& livor, std::size_t n) {
  const std::string src = "skin shading";
  auto same = [&](std::size_t got, const char* what) {
    require_input(got == n, src, what,
                  "has " + std::to_string(got) + " entries for " + std::to_string(n) + " vertices");
  };
  same(layers.vertex_epidermis.size(), "layers.vertex_epidermis");
  same(layers.vertex_absorption_hydrated.size(), "layers.vertex_absorption_hydrated");
  same(layers.vertex_absorption_dehydrated.size(), "layers.vertex_absorption_dehydrated");
  same(livor.vertex_hemoglobin.size(), "livor.vertex_hemoglobin");
  same(livor.vertex_capacity.size(), "livor.vertex_capacity");
  same(livor.vertex_oxygen.size(), "livor.vertex_oxygen");
}

}  // namespace

SkinLayers make_skin_layers(const std::vector<Vec3>& epidermis, const std::vector<double>& melanin_hydrated,
                            double dehydrated_factor, double epidermis_mm) {
  const std::string src = "skin layers";
  require_input(epidermis.size() == melanin_hydrated.size(), src, "melanin_hydrated",
                "has " + std::to_string(melanin_hydrated.size()) + " entries for " + std::to_string(epidermis.size()) +
                    " epidermis colours");
  require_input(std::isfinite(dehydrated_factor) && dehydrated_factor > 0.0, src, "dehydrated_factor",
                "must be positive");
  require_input(std::isfinite(epidermis_mm) && epidermis_mm > 0.0, src, "epidermis_mm", "must be positive");
  SkinLayers layers;
  const std::size_t n = epidermis.size();
  layers.vertex_epidermis = epidermis;
  layers.vertex_melanin_hydrated = melanin_hydrated;
  layers.vertex_melanin_dehydrated.resize(n);
  layers.vertex_absorption_hydrated.resize(n);
  layers.vertex_absorption_dehydrated.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    require_input(epidermis[i].allFinite() && epidermis[i].minCoeff() >= 0.0 && epidermis[i].maxCoeff() <= 1.0, src,
                  "epidermis[" + std::to_string(i) + "]", "must be in [0, 1]");
    require_input(std::isfinite(melanin_hydrated[i]) && melanin_hydrated[i] >= 0.0 && melanin_hydrated[i] <= 1.0, src,
                  "melanin_hydrated[" + std::to_string(i) + "]", "must be in [0, 1]");
  }
  parallel_for(0, n, [&](std::size_t i) {
    layers.vertex_melanin_dehydrated[i] = std::min(1.0, dehydrated_factor * melanin_hydrated[i]);
    layers.vertex_absorption_hydrated[i] = melanin_absorption(melanin_hydrated[i], epidermis_mm);
    layers.vertex_absorption_dehydrated[i] = melanin_absorption(layers.vertex_melanin_dehydrated[i], epidermis_mm);
  });
  return layers;
}

SkinLayers uniform_skin_layers(std::size_t vertices, const Vec3& epidermis, double melanin_hydrated,
                               double dehydrated_factor, double epidermis_mm) {
  SkinLayers one = make_skin_layers({epidermis}, {melanin_hydrated}, dehydrated_factor, epidermis_mm);
  SkinLayers layers;
  layers.vertex_epidermis.assign(vertices, one.vertex_epidermis[0]);
  layers.vertex_melanin_hydrated.assign(vertices, one.vertex_melanin_hydrated[0]);
  layers.vertex_melanin_dehydrated.assign(vertices, one.vertex_melanin_dehydrated[0]);
  layers.vertex_absorption_hydrated.assign(vertices, one.vertex_absorption_hydrated[0]);
  layers.vertex_absorption_dehydrated.assign(vertices, one.vertex_absorption_dehydrated[0]);
  return layers;
}

SkinShader::SkinShader(const SkinShadingSettings& settings) : m_settings(checked(settings)), m_lut(settings.lut) {}

double SkinShader::oxygen_at(double oxygen, double hours) const {
  return std::clamp(oxygen, 0.0, 1.0) * std::exp(-std::max(hours, 0.0) / m_settings.oxygen_decay_hours);
}

Vec3 SkinShader::shade_vertex(const Vec3& epidermis, const Vec3& absorption_hydrated, const Vec3& absorption_dehydrated,
                              double hemoglobin, double capacity, double oxygen, double moisture, double hours) const {
  const double m = std::clamp(moisture, 0.0, 1.0);
  const double s = hemoglobin_saturation(hemoglobin, capacity, m, m_settings.drying_boost);  // eq. 37
  const double d = degradation_level(oxygen_at(oxygen, hours), m);                           // eq. 38
  const Vec3 dermis = m_lut.sample(s, d);
  const Vec3 absorption = blend_melanin_absorption(absorption_hydrated, absorption_dehydrated, m);
  return combine_layers(epidermis, dermis, absorption, blended_weights(m));  // eqs. 36, 39
}

void SkinShader::shade(const SkinLayers& layers, const LivorState& livor, const std::vector<double>& vertex_moisture,
                       double hours, std::vector<Vec4f>& colours) const {
  const std::size_t n = vertex_moisture.size();
  check_sizes(layers, livor, n);
  require_input(std::isfinite(hours) && hours >= 0.0, "skin shading", "hours", "must be finite and >= 0");
  colours.resize(n);
  parallel_for_chunks(0, n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      colours[i] = rgba(shade_vertex(layers.vertex_epidermis[i], layers.vertex_absorption_hydrated[i],
                                     layers.vertex_absorption_dehydrated[i], livor.vertex_hemoglobin[i],
                                     livor.vertex_capacity[i], livor.vertex_oxygen[i], vertex_moisture[i], hours));
  });
}

std::vector<Vec4f> SkinShader::shade(const SkinLayers& layers, const LivorState& livor,
                                     const std::vector<double>& vertex_moisture, double hours) const {
  std::vector<Vec4f> colours;
  shade(layers, livor, vertex_moisture, hours, colours);
  return colours;
}

std::vector<Vec4f> livor_colours(const SkinLayers& layers, const LivorState& livor,
                                 const SkinShadingSettings& settings) {
  const std::size_t n = livor.vertex_hemoglobin.size();
  check_sizes(layers, livor, n);
  std::vector<Vec4f> colours(n);
  const ConvolutionWeights w = hydrated_weights();
  parallel_for(0, n, [&](std::size_t i) {
    const double s = std::clamp(livor.vertex_hemoglobin[i] * livor.vertex_capacity[i], 0.0, 1.0);
    const Vec3 dermis = livor_dermis_colour(s, livor.vertex_oxygen[i], settings.lut);
    colours[i] = rgba(combine_layers(layers.vertex_epidermis[i], dermis, layers.vertex_absorption_hydrated[i], w));
  });
  return colours;
}

double green_stage_moisture(const SkinShader& shader, double saturation, int steps) {
  require_input(steps >= 2, "green stage search", "steps", "must be >= 2");
  const SkinLayers layers = uniform_skin_layers(1);
  double best_m = 1.0, best = -1.0;
  for (int k = 0; k <= steps; ++k) {
    const double m = static_cast<double>(k) / steps;
    const Vec3 c = shader.shade_vertex(layers.vertex_epidermis[0], layers.vertex_absorption_hydrated[0],
                                       layers.vertex_absorption_dehydrated[0], saturation, 1.0, 0.0, m, 0.0);
    const double ratio = c[1] / std::max(c[0], 1e-12);
    if (ratio > best) {
      best = ratio;
      best_m = m;
    }
  }
  return best_m;
}

}  // namespace forensim
