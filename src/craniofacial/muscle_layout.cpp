#include "craniofacial/muscle_layout.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "geometry/mesh_measures.hpp"
#include "spatial/closest_point.hpp"

namespace forensim {
namespace {

struct LinearAnchor {
  const char* name;
  Vec3 origin, insertion;  // patient's left side (x >= 0); mirrored for _R
  double width_mm;
  bool bilateral;
};

struct SphincterAnchor {
  const char* name;
  Vec3 centre;
  double half_width_mm, half_height_mm;
  bool bilateral;
};

// Anchors on the head phantom's face (its eyes at z 19, mouth slit at z -43.5, cheilion near x 21).
const LinearAnchor linear_anchors[] = {
    {"frontalis", Vec3(24, -62, 105), Vec3(26, -86, 40), 36.0, true},
    {"corrugator_supercilii", Vec3(9, -90, 30), Vec3(30, -88, 38), 8.0, true},
    {"levator_labii_superioris_alaeque_nasi", Vec3(10, -92, 22), Vec3(14, -97, -31), 7.0, true},
    {"levator_labii_superioris", Vec3(25, -88, 5), Vec3(12, -98, -34), 11.0, true},
    {"zygomaticus_minor", Vec3(40, -78, 0), Vec3(16, -97, -36), 7.0, true},
    {"zygomaticus_major", Vec3(55, -62, -2), Vec3(22, -93, -42), 10.0, true},
    {"levator_anguli_oris", Vec3(24, -89, -14), Vec3(22, -93, -40), 8.0, true},
    {"risorius", Vec3(60, -44, -40), Vec3(23, -92, -43.5), 10.0, true},
    {"depressor_anguli_oris", Vec3(30, -72, -76), Vec3(22, -92, -46), 12.0, true},
    {"depressor_labii_inferioris", Vec3(15, -84, -72), Vec3(9, -96, -50), 10.0, true},
    {"procerus", Vec3(0, -101, 10), Vec3(0, -94, 36), 12.0, false},
};

const SphincterAnchor sphincter_anchors[] = {
    {"orbicularis_oris", Vec3(0, -96, -43.5), 27.0, 15.0, false},
    {"orbicularis_oculi", Vec3(32, -90, 19), 24.0, 19.0, true},
};

// The face's outward direction near a point: away from an axis through the head's centre.
Vec3 outward(const Vec3& p) {
  const Vec3 centre(0.0, 0.0, p.z());
  const Vec3 d = p - centre;
  return d.norm() > 0 ? d.normalized() : Vec3(0, -1, 0);
}

MuscleLayout linear_layout(const std::string& name, const Vec3& o, const Vec3& ins, double width, int fibres,
                           int samples) {
  MuscleLayout m;
  m.name = name;
  m.kind = MuscleKind::linear;
  m.fibre_count = fibres;
  m.samples_per_fibre = samples;
  const Vec3 along = ins - o;
  Vec3 side = along.cross(outward(0.5 * (o + ins)));
  side = side.norm() > 0 ? side.normalized() : Vec3::UnitX();
  for (int f = 0; f < fibres; ++f) {
    const double across = (static_cast<double>(f) / (fibres - 1) - 0.5) * width;
    for (int s = 0; s < samples; ++s) {
      const double t = static_cast<double>(s) / (samples - 1);
      // Fibres converge a little toward the insertion, as in the fan-shaped facial muscles.
      m.grid.push_back(o + t * along + (1.0 - 0.4 * t) * across * side);
    }
  }
  return m;
}

MuscleLayout sphincter_layout(const std::string& name, const Vec3& c, double a, double b, int fibres, int samples) {
  MuscleLayout m;
  m.name = name;
  m.kind = MuscleKind::sphincter;
  m.fibre_count = fibres;
  m.samples_per_fibre = samples;
  m.thickness_mm = 2.5;
  const Vec3 n = outward(c);
  const Vec3 e1 = (Vec3::UnitX() - n * n.x()).normalized();
  const Vec3 e2 = n.cross(e1).normalized() * (n.cross(e1).z() >= 0 ? 1.0 : -1.0);
  for (int f = 0; f < fibres; ++f) {
    const double scale = 0.55 + 0.45 * static_cast<double>(f) / (fibres - 1);
    for (int s = 0; s < samples; ++s) {
      const double theta = 2.0 * std::numbers::pi * s / samples;
      m.grid.push_back(c + scale * (a * std::cos(theta) * e1 + b * std::sin(theta) * e2));
    }
  }
  return m;
}

Vec3 mirror(const Vec3& p) {
  return Vec3(-p.x(), p.y(), p.z());
}

/// The right-side twin of a left-side muscle ("_L" becomes "_R"), point for point mirrored.
MuscleLayout mirrored_layout(const MuscleLayout& left) {
  MuscleLayout right = left;
  right.name = left.name.substr(0, left.name.size() - 2) + "_R";
  for (Vec3& p : right.grid) p = mirror(p);
  return right;
}

}  // namespace

std::vector<MuscleLayout> head_phantom_muscle_layouts(int fibre_count, int samples_per_fibre) {
  require_input(fibre_count >= 2 && fibre_count <= 64, "muscle layout", "fibre_count",
                "must be in [2, 64], got " + std::to_string(fibre_count));
  require_input(samples_per_fibre >= 3 && samples_per_fibre <= 256, "muscle layout", "samples_per_fibre",
                "must be in [3, 256], got " + std::to_string(samples_per_fibre));
  std::vector<MuscleLayout> out;
  for (const LinearAnchor& a : linear_anchors) {
    if (!a.bilateral) {
      out.push_back(linear_layout(a.name, a.origin, a.insertion, a.width_mm, fibre_count, samples_per_fibre));
      continue;
    }
    out.push_back(
        linear_layout(std::string(a.name) + "_L", a.origin, a.insertion, a.width_mm, fibre_count, samples_per_fibre));
    out.push_back(mirrored_layout(out.back()));
  }
  for (const SphincterAnchor& a : sphincter_anchors) {
    if (!a.bilateral) {
      out.push_back(
          sphincter_layout(a.name, a.centre, a.half_width_mm, a.half_height_mm, fibre_count, samples_per_fibre));
      continue;
    }
    out.push_back(sphincter_layout(std::string(a.name) + "_L", a.centre, a.half_width_mm, a.half_height_mm, fibre_count,
                                   samples_per_fibre));
    out.push_back(mirrored_layout(out.back()));
  }
  return out;
}

std::vector<std::string> facial_muscle_names() {
  std::vector<std::string> names;
  for (const MuscleLayout& m : head_phantom_muscle_layouts(2, 3)) names.push_back(m.name);
  return names;
}

std::vector<MuscleShape> shape_muscles(const std::vector<MuscleLayout>& layouts, const TriMesh& skin) {
  require_input(!skin.triangles.empty(), "muscle skin", "", "the skin mesh has no triangles");
  skin.validate("muscle skin");
  for (const MuscleLayout& m : layouts) {
    require_input(
        m.fibre_count >= 1 && m.samples_per_fibre >= 2 &&
            m.grid.size() == static_cast<std::size_t>(m.fibre_count) * static_cast<std::size_t>(m.samples_per_fibre),
        "muscle layout " + m.name, "grid",
        "has " + std::to_string(m.grid.size()) + " points for " + std::to_string(m.fibre_count) + " fibres of " +
            std::to_string(m.samples_per_fibre) + " samples");
    for (std::size_t i = 0; i < m.grid.size(); ++i) {
      if (!std::isfinite(m.grid[i].sum()))
        throw InputError("muscle layout " + m.name, "grid point " + std::to_string(i), "coordinates must be finite");
    }
    require_input(std::isfinite(m.thickness_mm) && m.thickness_mm >= 0.0, "muscle layout " + m.name, "thickness_mm",
                  "must be finite and non-negative");
  }
  std::vector<Vec3> normals = skin.normals;
  if (normals.size() != skin.positions.size()) {
    TriMesh copy = skin;
    compute_normals(copy);
    normals = copy.normals;
  }
  const ClosestPointQuery query(skin);
  std::vector<MuscleShape> shapes(layouts.size());
  for (std::size_t k = 0; k < layouts.size(); ++k) {
    const MuscleLayout& m = layouts[k];
    MuscleShape& s = shapes[k];
    s.name = m.name;
    s.kind = m.kind;
    s.fibre_count = m.fibre_count;
    s.samples_per_fibre = m.samples_per_fibre;
    const auto hits = query.query_batch(m.grid);
    const std::size_t n = m.grid.size();
    s.skin_points.resize(n);
    s.skin_triangles.resize(n);
    s.skin_barycentrics.resize(n);
    s.fibre_points.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const ClosestPoint& c = *hits[i];
      const Tri& t = skin.triangles[static_cast<std::size_t>(c.triangle)];
      Vec3 normal = c.barycentric(0) * normals[static_cast<std::size_t>(t[0])] +
                    c.barycentric(1) * normals[static_cast<std::size_t>(t[1])] +
                    c.barycentric(2) * normals[static_cast<std::size_t>(t[2])];
      normal = normal.norm() > 0 ? normal.normalized() : Vec3::Zero();
      s.skin_points[i] = c.point;
      s.skin_triangles[i] = c.triangle;
      s.skin_barycentrics[i] = c.barycentric;
      s.fibre_points[i] = c.point - m.thickness_mm * normal;
    }
    const bool closed = m.kind == MuscleKind::sphincter;
    for (int f = 0; f < m.fibre_count; ++f) {
      double length = 0.0;
      const std::size_t base = static_cast<std::size_t>(f) * static_cast<std::size_t>(m.samples_per_fibre);
      for (int j = 0; j + 1 < m.samples_per_fibre; ++j) {
        length += (s.fibre_points[base + static_cast<std::size_t>(j) + 1] -
                   s.fibre_points[base + static_cast<std::size_t>(j)])
                      .norm();
      }
      if (closed) {
        length +=
            (s.fibre_points[base] - s.fibre_points[base + static_cast<std::size_t>(m.samples_per_fibre) - 1]).norm();
      }
      s.fibre_lengths_mm.push_back(length);
    }
  }
  return shapes;
}

}  // namespace forensim
