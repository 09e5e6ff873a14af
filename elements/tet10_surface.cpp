// SPDX-License-Identifier: GPL-3.0-or-later
#include "elements/tet10_surface.hpp"

#include <algorithm>
#include <tuple>

namespace femdem {

std::vector<BoundaryFace> boundary_faces(const std::vector<Tet10>& elements) {
  // Sort the faces by their sorted corner triple; a face that appears once is on the boundary.
  struct Key {
    std::int32_t a, b, c;
    std::int32_t element;
    std::int8_t face;
  };
  std::vector<Key> keys;
  keys.reserve(elements.size() * 4);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (int f = 0; f < 4; ++f) {
      std::int32_t v[3] = {elements[e][kTet10Faces[f][0]], elements[e][kTet10Faces[f][1]],
                           elements[e][kTet10Faces[f][2]]};
      std::sort(v, v + 3);
      keys.push_back({v[0], v[1], v[2], static_cast<std::int32_t>(e), static_cast<std::int8_t>(f)});
    }
  }
  auto corners = [](const Key& k) { return std::tie(k.a, k.b, k.c); };
  std::sort(keys.begin(), keys.end(), [&](const Key& p, const Key& q) {
    return std::tie(p.a, p.b, p.c, p.element, p.face) < std::tie(q.a, q.b, q.c, q.element, q.face);
  });
  std::vector<BoundaryFace> out;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && corners(keys[j]) == corners(keys[i])) ++j;
    if (j - i == 1) out.push_back({keys[i].element, keys[i].face});
    i = j;
  }
  std::sort(out.begin(), out.end(), [](const BoundaryFace& p, const BoundaryFace& q) {
    return std::tie(p.element, p.face) < std::tie(q.element, q.face);
  });
  return out;
}

}  // namespace femdem
