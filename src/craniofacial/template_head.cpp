#include "craniofacial/template_head.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <unordered_map>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/timer.hpp"
#include "geometry/mesh_measures.hpp"
#include "geometry/mesh_topology.hpp"
#include "mesh_processing/remesh_isotropic.hpp"
#include "mesh_processing/uv_atlas.hpp"
#include "phantoms/head_phantom.hpp"
#include "phantoms/phantom_surface.hpp"
#include "spatial/closest_point.hpp"
#include "spatial/ray_caster.hpp"

namespace forensim {
namespace {

const HeadPhantom& phantom() {
  static const HeadPhantom head;
  return head;
}

double bone(const Vec3& p) {
  return phantom().bone_distance(p);
}

/// First point of o + t d (t in (0, t_max], d unit) inside the phantom's skin (as march() for bone).
std::optional<Vec3> march_skin(const Vec3& o, const Vec3& d, double t_max) {
  double t0 = 0.0;
  double f0 = phantom().skin_distance(o);
  if (f0 <= 0.0) return std::nullopt;
  while (t0 < t_max) {
    const double t1 = std::min(t_max, t0 + std::max(0.2, 0.5 * f0));
    const double f1 = phantom().skin_distance(o + t1 * d);
    if (f1 <= 0.0) {
      double a = t0, b = t1;
      for (int i = 0; i < 60 && b - a > 1e-7; ++i) {
        const double m = 0.5 * (a + b);
        (phantom().skin_distance(o + m * d) <= 0.0 ? b : a) = m;
      }
      return o + b * d;
    }
    t0 = t1;
    f0 = f1;
  }
  return std::nullopt;
}

/// The head phantom seen only over its skull (above the third cervical vertebra): the bone surface is sampled
/// over 57 % of the head's box.
class SkullRegion final : public Phantom {
 public:
  std::string name() const override { return "head skull"; }
  double skin_distance(const Vec3& p) const override { return phantom().skin_distance(p); }
  double bone_distance(const Vec3& p) const override { return phantom().bone_distance(p); }
  BoundingBox bounds() const override {
    BoundingBox box;
    box.extend(Vec3(-80, -105, -95));
    box.extend(Vec3(80, 115, 146));
    return box;
  }
  const std::vector<std::string>& part_names() const override { return phantom().part_names(); }
  int part_at(const Vec3& p) const override { return phantom().part_at(p); }
};

/// First point of o + t d (t in (0, t_max], d unit) inside the phantom's bone, by sphere tracing with half
/// steps (the smooth unions make the distance a bound, not exact) and bisection to 1e-6 mm. None when the ray
/// starts inside bone or misses.
std::optional<Vec3> march(const Vec3& o, const Vec3& d, double t_max) {
  double t0 = 0.0;
  double f0 = bone(o);
  if (f0 <= 0.0) return std::nullopt;
  while (t0 < t_max) {
    const double t1 = std::min(t_max, t0 + std::max(0.2, 0.5 * f0));
    const double f1 = bone(o + t1 * d);
    if (f1 <= 0.0) {
      double a = t0, b = t1;
      for (int i = 0; i < 60 && b - a > 1e-7; ++i) {
        const double m = 0.5 * (a + b);
        (bone(o + m * d) <= 0.0 ? b : a) = m;
      }
      return o + b * d;
    }
    t0 = t1;
    f0 = f1;
  }
  return std::nullopt;
}

Vec3 bone_gradient(const Vec3& p) {
  constexpr double h = 0.2;
  return Vec3(bone(p + Vec3(h, 0, 0)) - bone(p - Vec3(h, 0, 0)), bone(p + Vec3(0, h, 0)) - bone(p - Vec3(0, h, 0)),
              bone(p + Vec3(0, 0, h)) - bone(p - Vec3(0, 0, h)))
      .normalized();
}

/// The skull's outward normal at p averaged over a small patch (as the paper orients its depth markers): the
/// mean of the bone distance's unit gradients at the 27 points of a 2 mm lattice around p, so a landmark in a
/// crease (where alveolar bone meets a tooth) gets the direction of the surface around it.
Vec3 bone_normal(const Vec3& p) {
  Vec3 sum = Vec3::Zero();
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      for (int k = -1; k <= 1; ++k) sum += bone_gradient(p + 2.0 * Vec3(i, j, k));
    }
  }
  return sum.norm() > 0 ? sum.normalized() : bone_gradient(p);
}

[[noreturn]] void not_found(const std::string& name) {
  throw NumericError("template head: landmark '" + name + "' not found on the head phantom's skull");
}

Vec3 required(const std::optional<Vec3>& p, const std::string& name) {
  if (!p) not_found(name);
  return *p;
}

/// The midsagittal anterior profile: the first bone point of rays along +y at x = 0, z from high to low.
struct Profile {
  std::vector<double> z;
  std::vector<std::optional<Vec3>> point;
  std::size_t size() const { return z.size(); }
  bool hit(std::size_t i) const { return point[i].has_value(); }
  double y(std::size_t i) const { return point[i]->y(); }
  /// Index of the sample nearest to height z.
  std::size_t at(double height) const {
    std::size_t best = 0;
    for (std::size_t i = 1; i < z.size(); ++i) best = std::abs(z[i] - height) < std::abs(z[best] - height) ? i : best;
    return best;
  }
};

Profile midline_profile(double z_top, double z_bottom, double dz) {
  Profile p;
  for (double z = z_top; z >= z_bottom; z -= dz) {
    p.z.push_back(z);
    p.point.push_back(march(Vec3(0, -150, z), Vec3(0, 1, 0), 250));
  }
  return p;
}

/// The deepest (most posterior, relative to the chord between samples a and b) profile point strictly between
/// them; when none lies behind the chord by 0.2 mm (a convex stretch), the sample a third of the way.
std::size_t deepest_between(const Profile& p, std::size_t a, std::size_t b) {
  const Vec3 pa = *p.point[a], pb = *p.point[b];
  const Vec2 chord(pb.y() - pa.y(), pb.z() - pa.z());
  const Vec2 normal = Vec2(chord.y(), -chord.x()).normalized();  // points to +y (posterior) for a downward chord
  std::size_t best = a + (b - a) / 3;
  double depth = 0.2;
  for (std::size_t i = a + 1; i < b; ++i) {
    if (!p.hit(i)) continue;
    const Vec2 rel(p.y(i) - pa.y(), p.z[i] - pa.z());
    const double d = rel.dot(normal) * (normal.x() >= 0 ? 1.0 : -1.0);
    if (d > depth) {
      depth = d;
      best = i;
    }
  }
  return best;
}

Vec3 mirrored(const Vec3& p) {
  return Vec3(-p.x(), p.y(), p.z());
}

/// Extreme bone point over a grid of parallel rays: rays start at origin(u, v) and go along `dir`; the hit
/// maximising score(hit) wins.
template <class Origin, class Score>
std::optional<Vec3> extreme_hit(double u0, double u1, double v0, double v1, double step, const Vec3& dir, double t_max,
                                Origin origin, Score score) {
  std::optional<Vec3> best;
  double best_score = -1e300;
  for (double u = u0; u <= u1 + 1e-9; u += step) {
    for (double v = v0; v <= v1 + 1e-9; v += step) {
      const auto hit = march(origin(u, v), dir, t_max);
      if (hit && score(*hit) > best_score) {
        best_score = score(*hit);
        best = hit;
      }
    }
  }
  return best;
}

// The phantom's design (head_phantom.cpp): orbit centre, tooth positions on the dental arch.
const Vec3 orbit_centre(32.0, -68.0, 18.0);
constexpr double nasal_bone_top_z = 24.0;
Vec2 tooth_xy(int t) {
  const double angle = (t + 0.5) / 8.0 * 1.35;
  return Vec2(std::sin(angle) * 24.0, -78.0 + (1.0 - std::cos(angle)) * 34.0);
}

/// Gives every piece of a chart other than its largest to the neighbouring chart it shares most edges with,
/// and a triangle with two or more neighbours in one other chart to that chart (a straighter seam). Returns
/// the triangles moved.
std::size_t clean_charts(const std::vector<std::array<std::int32_t, 3>>& nb, std::vector<int>& chart) {
  const std::size_t n = chart.size();
  std::size_t moved = 0;
  for (std::size_t t = 0; t < n; ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (nb[t][k] < 0) continue;
      const int other = chart[static_cast<std::size_t>(nb[t][k])];
      if (other == chart[t]) continue;
      int count = 0;
      for (const std::int32_t u : nb[t]) count += u >= 0 && chart[static_cast<std::size_t>(u)] == other ? 1 : 0;
      if (count >= 2) {
        chart[t] = other;
        ++moved;
        break;
      }
    }
  }
  return moved + merge_chart_islands(nb, chart);
}

constexpr double top_chart_z = 100.0;     // above: the crown of the head
constexpr double neck_cut_z = -150.0;     // HeadPhantom's flat neck cut
constexpr double face_half_angle = 55.0;  // degrees of azimuth either side of the face's midline
constexpr double back_half_angle = 35.0;  // degrees either side of the back's midline

/// Charts: 0 top (crown), 1 bottom (neck cut), then four azimuth bands from the neck to the crown: 2 face,
/// 3 left, 4 right, 5 back. Each band is a disk between the crown's rim and the neck's.
std::vector<int> assign_charts(const TriMesh& mesh) {
  const std::vector<Vec3> n = face_normals(mesh);
  std::vector<int> chart(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& f = mesh.triangles[t];
    const Vec3 c = (mesh.positions[static_cast<std::size_t>(f[0])] + mesh.positions[static_cast<std::size_t>(f[1])] +
                    mesh.positions[static_cast<std::size_t>(f[2])]) /
                   3.0;
    const double azimuth = std::atan2(c.x(), -c.y()) * 180.0 / std::numbers::pi;
    if (c.z() > top_chart_z) {
      chart[t] = 0;
    } else if (c.z() < neck_cut_z + 1.0 && n[t].z() < -0.9) {
      chart[t] = 1;
    } else if (std::abs(azimuth) <= face_half_angle) {
      chart[t] = 2;
    } else if (std::abs(azimuth) >= 180.0 - back_half_angle) {
      chart[t] = 5;
    } else {
      chart[t] = azimuth > 0 ? 3 : 4;
    }
  }
  return chart;
}

/// Drops the cervical spine from the phantom's bone surface: components whose centre lies below the skull base
/// behind the face.
TriMesh skull_only(const TriMesh& bone_mesh) {
  int count = 0;
  const std::vector<int> comp = triangle_components(bone_mesh, &count);
  std::vector<Vec3> centre(static_cast<std::size_t>(count), Vec3::Zero());
  std::vector<double> weight(static_cast<std::size_t>(count), 0.0);
  for (std::size_t t = 0; t < bone_mesh.triangles.size(); ++t) {
    const Tri& f = bone_mesh.triangles[t];
    for (const Index v : f)
      centre[static_cast<std::size_t>(comp[t])] += bone_mesh.positions[static_cast<std::size_t>(v)];
    weight[static_cast<std::size_t>(comp[t])] += 3.0;
  }
  std::vector<bool> keep(bone_mesh.triangles.size());
  for (std::size_t t = 0; t < keep.size(); ++t) {
    const Vec3 c = centre[static_cast<std::size_t>(comp[t])] / weight[static_cast<std::size_t>(comp[t])];
    // Vertebrae (and pieces of them cut by the sampling box's floor) lie behind and below the face.
    keep[t] = !(c.z() < -30.0 && c.y() > 5.0 && std::abs(c.x()) < 20.0);
  }
  return extract_triangles(bone_mesh, keep);
}

// The phantom's mouth slit (head_phantom.cpp): its lateral end and height.
const Vec3 mouth_slit_corner(21.0, -92.0, -43.5);

/// The skin-only landmarks on the phantom's skin (before projection onto the skin mesh).
std::vector<TemplateSkinLandmark> phantom_skin_landmarks() {
  std::vector<TemplateSkinLandmark> out;
  std::optional<Vec3> prn;
  for (double z = -30.0; z <= 20.0; z += 0.25) {
    const auto hit = march_skin(Vec3(0, -160, z), Vec3(0, 1, 0), 200.0);
    if (hit && (!prn || hit->y() < prn->y())) prn = hit;
  }
  std::optional<Vec3> al;
  for (double y = -102.0; y <= -94.0; y += 0.25) {
    for (double z = -25.0; z <= -5.0; z += 0.25) {
      const auto hit = march_skin(Vec3(40, y, z), Vec3(-1, 0, 0), 40.0);
      if (hit && hit->x() < 30.0 && (!al || hit->x() > al->x())) al = hit;
    }
  }
  const auto sto = march_skin(Vec3(0, -160, mouth_slit_corner.z()), Vec3(0, 1, 0), 200.0);
  if (!prn) not_found("prn'");
  if (!al) not_found("al'");
  if (!sto) not_found("sto'");
  out.push_back({"prn'", *prn});
  out.push_back({"al'_L", *al});
  out.push_back({"al'_R", mirrored(*al)});
  out.push_back({"ch'_L", mouth_slit_corner});
  out.push_back({"ch'_R", mirrored(mouth_slit_corner)});
  out.push_back({"sto'", *sto});
  return out;
}

}  // namespace

std::vector<PhantomSkullLandmark> head_phantom_skull_landmarks() {
  std::vector<PhantomSkullLandmark> out;
  auto add = [&](const std::string& bone_name, const std::string& skin_name, const Vec3& p, bool midline) {
    out.push_back({bone_name, skin_name, p, bone_normal(p), midline});
  };
  auto add_pair = [&](const std::string& bone_name, const std::string& skin_name, const Vec3& p_left) {
    PhantomSkullLandmark left{bone_name + "_L", skin_name + "_L", p_left, bone_normal(p_left), false};
    PhantomSkullLandmark right{bone_name + "_R", skin_name + "_R", mirrored(p_left), mirrored(left.normal), false};
    out.push_back(left);
    out.push_back(right);
  };

  // Midsagittal profile, 0.25 mm apart from the brow to below the chin.
  const Profile prof = midline_profile(60.0, -90.0, 0.25);
  // Nasion: the nasofrontal suture on the midline, which on the phantom is the top of its nasal bones
  // (head_phantom.cpp); the phantom's profile has no concavity there to find it by.
  const std::size_t n = prof.at(nasal_bone_top_z);
  if (!prof.hit(n)) not_found("n");
  // Glabella: the most anterior midline point of the frontal bone above nasion, between the brow ridges.
  std::optional<std::size_t> g;
  for (std::size_t i = 0; i < n; ++i) {
    if (prof.hit(i) && prof.z[i] >= prof.z[n] + 3.0 && prof.z[i] <= 50.0 && (!g || prof.y(i) < prof.y(*g))) g = i;
  }
  if (!g) not_found("g");
  // Down from nasion along the nasal bones until the profile falls back into the nasal aperture.
  std::size_t rhi = n;
  while (rhi + 1 < prof.size() && prof.hit(rhi + 1) && prof.y(rhi + 1) - prof.y(rhi) < 4.0) ++rhi;
  if (rhi == n) not_found("rhi");
  const std::size_t mn = prof.at(0.5 * (prof.z[n] + prof.z[rhi]));
  // Below the aperture: the floor where the maxilla's front returns, then the upper incisor's edge.
  std::size_t floor = rhi + 1;
  while (floor < prof.size() && !(prof.hit(floor) && prof.y(floor) < -70.0)) ++floor;
  std::size_t pr = floor;
  while (pr + 1 < prof.size() && prof.hit(pr + 1) && prof.y(pr + 1) > prof.y(pr) - 1.0) ++pr;
  if (floor >= prof.size() || pr + 1 >= prof.size() || pr == floor) not_found("pr");
  const std::size_t ss = deepest_between(prof, floor, pr);
  const std::size_t mp = prof.at(0.5 * (prof.z[ss] + prof.z[pr]));
  // Chin: pogonion, then up to the lower incisor's edge.
  std::optional<std::size_t> pg;
  for (std::size_t i = 0; i < prof.size(); ++i) {
    if (prof.hit(i) && prof.z[i] <= -53.0 && prof.z[i] >= -80.0 && (!pg || prof.y(i) < prof.y(*pg))) pg = i;
  }
  if (!pg) not_found("pg");
  std::size_t id = *pg;
  while (id > 0 && prof.hit(id - 1) && prof.y(id - 1) > prof.y(id) - 1.0) --id;
  if (id == 0 || id == *pg) not_found("id");
  const std::size_t sm = deepest_between(prof, id, *pg);
  const Vec3 me = required(extreme_hit(
                               -85.0, -55.0, 0.0, 0.0, 0.5, Vec3(0, 0, 1), 120.0,
                               [](double y, double) { return Vec3(0, y, -140); }, [](const Vec3& p) { return -p.z(); }),
                           "me");
  const Vec3 diagonal = Vec3(0, -1, -1).normalized();
  const Vec3 mid = 0.5 * (*prof.point[*pg] + me);
  const Vec3 gn = required(march(mid + 40.0 * diagonal, -diagonal, 60.0), "gn");
  const Vec3 v = required(extreme_hit(
                              -60.0, 80.0, 0.0, 0.0, 0.5, Vec3(0, 0, -1), 200.0,
                              [](double y, double) { return Vec3(0, y, 160); }, [](const Vec3& p) { return p.z(); }),
                          "v");
  const Vec3 op = required(extreme_hit(
                               -10.0, 110.0, 0.0, 0.0, 0.5, Vec3(0, -1, 0), 200.0,
                               [](double z, double) { return Vec3(0, 150, z); }, [](const Vec3& p) { return p.y(); }),
                           "op");

  add("op", "op'", op, true);
  add("v", "v'", v, true);
  add("g", "g'", *prof.point[*g], true);
  add("n", "se'", *prof.point[n], true);
  add("mn", "mn'", *prof.point[mn], true);
  add("rhi", "rhi'", *prof.point[rhi], true);
  add("ss", "sn'", *prof.point[ss], true);
  add("mp", "mp'", *prof.point[mp], true);
  add("pr", "ls'", *prof.point[pr], true);
  add("id", "li'", *prof.point[id], true);
  add("sm", "sm'", *prof.point[sm], true);
  add("pg", "pg'", *prof.point[*pg], true);
  add("gn", "gn'", gn, true);
  add("me", "me'", me, true);

  // Bilateral, found on the left (x > 0) and mirrored: the phantom is symmetric.
  const Vec3 mso = required(
      extreme_hit(
          24.0, 42.0, 0.0, 0.0, 0.25, Vec3(0, 1, 0), 250.0,
          [](double z, double) { return Vec3(orbit_centre.x(), -150, z); }, [](const Vec3& p) { return -p.y(); }),
      "mso");
  const Vec3 mio = required(
      extreme_hit(
          -4.0, 12.0, 0.0, 0.0, 0.25, Vec3(0, 1, 0), 250.0,
          [](double z, double) { return Vec3(orbit_centre.x(), -150, z); }, [](const Vec3& p) { return -p.y(); }),
      "mio");
  // Nasal aperture: its half-width along +x just behind the maxilla's front, widest over z.
  double aperture_x = 0.0, aperture_z = 0.0;
  for (double z = -16.0; z <= 8.0; z += 0.5) {
    const auto hit = march(Vec3(0, -76, z), Vec3(1, 0, 0), 40.0);
    if (hit && hit->x() > aperture_x) {
      aperture_x = hit->x();
      aperture_z = z;
    }
  }
  if (aperture_x <= 0.0) not_found("ac");
  const Vec3 ac = required(march(Vec3(aperture_x + 5.0, -150, aperture_z), Vec3(0, 1, 0), 250.0), "ac");
  const Vec3 zy = required(extreme_hit(
                               -55.0, 5.0, -6.0, 8.0, 1.0, Vec3(-1, 0, 0), 150.0,
                               [](double y, double z) { return Vec3(150, y, z); }, [](const Vec3& p) { return p.x(); }),
                           "zy");
  // Mandible in side view: its silhouette (rays along -x that hit bone lateral of x = 20 mm).
  const Vec3 back_down = Vec3(0, 1, -1).normalized();
  std::vector<Vec3> silhouette;
  for (double y = -40.0; y <= 15.0; y += 1.0) {
    for (double z = -75.0; z <= -8.0; z += 1.0) {
      const auto hit = march(Vec3(150, y, z), Vec3(-1, 0, 0), 130.0);
      if (hit && hit->x() > 20.0) silhouette.push_back(*hit);
    }
  }
  if (silhouette.empty()) not_found("go");
  const Vec3 angle = *std::max_element(silhouette.begin(), silhouette.end(), [&](const Vec3& a, const Vec3& b) {
    return a.dot(back_down) < b.dot(back_down);
  });
  const Vec3 inward = angle - 3.0 * back_down;
  const Vec3 go = required(march(Vec3(150, inward.y(), inward.z()), Vec3(-1, 0, 0), 150.0), "go");
  double ramus_top = go.z();
  for (const Vec3& p : silhouette) ramus_top = p.y() > -30.0 ? std::max(ramus_top, p.z()) : ramus_top;
  const double mr_z = std::round(0.5 * (go.z() + ramus_top));
  double y_lo = 1e9, y_hi = -1e9;
  for (const Vec3& p : silhouette) {
    if (std::abs(p.z() - mr_z) < 0.5 && p.y() > -40.0) {
      y_lo = std::min(y_lo, p.y());
      y_hi = std::max(y_hi, p.y());
    }
  }
  if (y_lo > y_hi) not_found("mr");
  const Vec3 mr = required(march(Vec3(150, 0.5 * (y_lo + y_hi), mr_z), Vec3(-1, 0, 0), 150.0), "mr");
  // The lowest point of the mandible's cross-section halfway between gonion and menton.
  const double border_y = 0.5 * (go.y() + me.y());
  const Vec3 mmb =
      required(extreme_hit(
                   5.0, 55.0, 0.0, 0.0, 0.5, Vec3(0, 0, 1), 120.0,
                   [&](double x, double) { return Vec3(x, border_y, -140); }, [](const Vec3& p) { return -p.z(); }),
               "mmb");
  const Vec2 canine = tooth_xy(2), molar2 = tooth_xy(6);
  const Vec3 sC = required(march(Vec3(canine.x(), -150, -30), Vec3(0, 1, 0), 250.0), "sC");
  const Vec3 iC = required(march(Vec3(canine.x(), -150, -56), Vec3(0, 1, 0), 250.0), "iC");
  const Vec3 ecm2_upper = required(march(Vec3(150, molar2.y(), -33), Vec3(-1, 0, 0), 150.0), "ecm2");
  const Vec3 ecm2_lower = required(march(Vec3(150, molar2.y(), -53), Vec3(-1, 0, 0), 150.0), "ecm2");

  add_pair("mso", "mso'", mso);
  add_pair("mio", "mio'", mio);
  add_pair("ac", "ac'", ac);
  add_pair("go", "go'", go);
  add_pair("zy", "zy'", zy);
  add_pair("sC", "sC'", sC);
  add_pair("iC", "iC'", iC);
  add_pair("ecm2", "sM2'", ecm2_upper);
  add_pair("ecm2", "iM2'", ecm2_lower);
  add_pair("mr", "mr'", mr);
  add_pair("mmb", "mmb'", mmb);
  return out;
}

TemplateHeadOptions template_head_options(const std::string& detail) {
  TemplateHeadOptions o;
  if (detail == "coarse") {
    o.skin_voxel_mm = 3.0;
    o.skin_edge_mm = 6.0;
    o.skull_voxel_mm = 3.0;
    o.remesh_iterations = 2;
    o.uv_resolution = 512;
  } else if (detail != "full") {
    throw InputError("template detail", detail, "unknown (known: full, coarse)");
  }
  return o;
}

namespace {

void check_options(const TemplateHeadOptions& options) {
  const char* const source = "template head options";
  require_input(options.skin_voxel_mm >= 0.5 && options.skin_voxel_mm <= 5.0, source, "skin_voxel_mm",
                "must be in [0.5, 5], got " + std::to_string(options.skin_voxel_mm));
  require_input(options.skull_voxel_mm >= 0.5 && options.skull_voxel_mm <= 5.0, source, "skull_voxel_mm",
                "must be in [0.5, 5], got " + std::to_string(options.skull_voxel_mm));
  require_input(options.skin_edge_mm >= 0.5 * options.skin_voxel_mm && options.skin_edge_mm <= 15.0, source,
                "skin_edge_mm", "must be in [skin_voxel_mm / 2, 15], got " + std::to_string(options.skin_edge_mm));
  require_input(options.remesh_iterations >= 0 && options.remesh_iterations <= 20, source, "remesh_iterations",
                "must be in [0, 20]");
  require_input(options.uv_resolution >= 64 && options.uv_resolution <= 16384, source, "uv_resolution",
                "must be in [64, 16384]");
}

}  // namespace

TemplateHead make_template_skull(const TemplateHeadOptions& options) {
  check_options(options);
  Stopwatch watch;
  TemplateHead head;
  head.skull = skull_only(phantom_surface(SkullRegion(), PhantomSurface::bone, options.skull_voxel_mm));
  compute_normals(head.skull);
  // The skull landmarks: the definitions on the phantom's bone, moved onto the skull mesh (their skin points come
  // with the skin, join_template_head). A few dozen points: every triangle tested, side by side over the landmarks,
  // costs less than building a tree for them (the same closest points).
  const std::vector<PhantomSkullLandmark> definitions = head_phantom_skull_landmarks();
  head.landmarks.resize(definitions.size());
  parallel_for(
      0, definitions.size(),
      [&](std::size_t i) {
        const PhantomSkullLandmark& l = definitions[i];
        TemplateLandmarkPair& pair = head.landmarks[i];
        pair.bone_name = l.bone_name;
        pair.skin_name = l.skin_name;
        pair.midline = l.midline;
        pair.skull = closest_point(head.skull, l.position)->point;
        pair.skull_normal = l.normal;
      },
      1);
  head.seconds_skull = watch.seconds();
  head.seconds = head.seconds_skull;
  return head;
}

TemplateSkin make_template_skin(const TemplateHeadOptions& options) {
  check_options(options);
  Stopwatch watch;
  TemplateSkin out;
  out.surface =
      keep_largest_components(remesh_isotropic(phantom_surface(phantom(), PhantomSurface::skin, options.skin_voxel_mm),
                                               options.skin_edge_mm, options.remesh_iterations),
                              1);
  compute_normals(out.surface);
  out.seconds_surface = watch.lap();
  if (!options.uv_atlas) out.skin = out.surface;
  if (options.uv_atlas) {
    // The UV atlas cuts the skin along its seams.
    out.triangle_chart = assign_charts(out.surface);
    const auto nb = triangle_edge_neighbours(out.surface);
    for (int round = 0; round < 50 && clean_charts(nb, out.triangle_chart) > 0; ++round) {
    }
    UvAtlasOptions atlas_options;
    atlas_options.resolution = options.uv_resolution;
    UvAtlas atlas = make_uv_atlas(out.surface, out.triangle_chart, atlas_options);
    out.skin = std::move(atlas.mesh);
    out.uv_l2_stretch = atlas.stats.l2_stretch;
    out.uv_overlap_free = atlas.stats.overlap_free;
  }
  out.chart_names = {"top", "bottom", "face", "left", "right", "back"};
  out.muscles = head_phantom_muscle_layouts(options.muscle_fibres, options.muscle_samples);
  const ClosestPointQuery on_skin(out.skin);
  for (MuscleLayout& m : out.muscles) {
    for (Vec3& p : m.grid) p = on_skin.query(p)->point;
  }
  out.seconds_atlas = watch.lap();
  return out;
}

TemplateHead join_template_head(TemplateHead skull_part, TemplateSkin skin) {
  require_input(!skull_part.skull.triangles.empty() && !skull_part.landmarks.empty(), "template head", "skull part",
                "has no skull or landmarks (make_template_skull)");
  require_input(!skin.surface.triangles.empty(), "template head", "skin part", "has no skin (make_template_skin)");
  Stopwatch watch;
  TemplateHead head = std::move(skull_part);
  // The skin where each skull landmark's normal meets it, on the skin as remeshed (before the atlas's cuts).
  const RayCaster skin_rays(skin.surface);
  for (TemplateLandmarkPair& pair : head.landmarks) {
    const auto hit = skin_rays.intersect(pair.skull, pair.skull_normal, 0.0, 80.0);
    if (!hit) throw NumericError("template head: the normal at skull landmark " + pair.bone_name + " misses the skin");
    pair.skin = hit->point;
    pair.depth_mm = hit->t;
  }
  const ClosestPointQuery skin_points(skin.surface);
  head.skin_landmarks.clear();
  for (TemplateSkinLandmark l : phantom_skin_landmarks()) {
    l.position = skin_points.query(l.position)->point;
    head.skin_landmarks.push_back(l);
  }
  head.skin = std::move(skin.skin);
  head.triangle_chart = std::move(skin.triangle_chart);
  head.chart_names = std::move(skin.chart_names);
  head.uv_l2_stretch = skin.uv_l2_stretch;
  head.uv_overlap_free = skin.uv_overlap_free;
  head.muscles = std::move(skin.muscles);
  head.seconds_skin = skin.seconds_surface;
  head.seconds_atlas = skin.seconds_atlas;
  head.seconds_landmarks = watch.seconds();
  return head;
}

TemplateHead make_template_head_beside(const TemplateHeadOptions& options,
                                       const std::function<void(const TemplateHead& skull_part)>& with_skull) {
  check_options(options);
  Stopwatch watch;
  TemplateHead skull_part;
  TemplateSkin skin;
  // The skin and the skull are independent: built side by side (the skin's remeshing runs on one thread).
  parallel_invoke([&] { skin = make_template_skin(options); },
                  [&] {
                    skull_part = make_template_skull(options);
                    if (with_skull) with_skull(skull_part);
                  });
  TemplateHead head = join_template_head(std::move(skull_part), std::move(skin));
  head.seconds = watch.seconds();
  return head;
}

TemplateHead make_template_head(const TemplateHeadOptions& options) {
  return make_template_head_beside(options, nullptr);
}

int find_template_landmark(const TemplateHead& head, const std::string& name) {
  for (std::size_t i = 0; i < head.landmarks.size(); ++i) {
    if (head.landmarks[i].skin_name == name) return static_cast<int>(i);
  }
  int found = -1;
  for (std::size_t i = 0; i < head.landmarks.size(); ++i) {
    if (head.landmarks[i].bone_name != name) continue;
    if (found >= 0) {
      throw InputError("landmark name", name,
                       "pairs with several template skin landmarks (" +
                           head.landmarks[static_cast<std::size_t>(found)].skin_name + ", " +
                           head.landmarks[i].skin_name + "); use the skin landmark's name");
    }
    found = static_cast<int>(i);
  }
  return found;
}

}  // namespace forensim
