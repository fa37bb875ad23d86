#pragma once
/// The template head carried onto a target skull by the registration of its skull, before the landmark warp
/// (beyond Kähler, Haber and Seidel 2003, who fit the template by the warp of eq. 1 on the landmark pairs alone).
///
/// The automatic landmarks come from registering the template's skull onto the target's (skull_registration.hpp:
/// a similarity, then a smooth displacement field). The head lies on that skull, so every point of it is carried
/// by the same map: skin vertices, skull, muscle layout grids, skin-only landmarks and the landmark pairs. The
/// warp of eq. 1 then only has to set the tissue depths at the landmarks, instead of also bending a generic skull's
/// head onto a particular skull between them. On the headsq CT with the built-in template, the skull and skin
/// vertices on the wrong side after the warp with the given pairs alone fell from 15,631 to 3,395, and the share
/// of the real face within 2.5 mm rose from 52.5 to 58.8 % (coarse template 51.7 to 63.5 %; bone at 1150 55.4 to
/// 63.1 %; `forensim reconstruct --evaluate`, without and with `--no-carry`).

#include "craniofacial/skull_registration.hpp"
#include "craniofacial/template_head.hpp"

namespace forensim {

/// `head` with every position mapped by `registration` (SkullRegistration::map; `registration` must map `head`'s
/// skull, i.e. have been made with it as the reference). Skin and skull get new vertex normals (their triangles,
/// UVs and charts are kept). Each landmark pair keeps its two points as one segment: its skull and skin points
/// are mapped, its direction is the mapped segment's and its depth the mapped segment's length. `source` records
/// the carry. Parallel over the points and deterministic (each point is mapped on its own). Throws InputError
/// naming "template head" when the head has no skin or no skull, and when a mapped position is not finite.
TemplateHead carry_template_head(const TemplateHead& head, const SkullRegistration& registration);

}  // namespace forensim
