// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The contact laws a scene can choose: `[contact] law` between bodies (a law of
// contact/body_pair_law.hpp) and `[contact] wall_law` between bodies and walls (a law of
// contact/penalty_wall_law.hpp's form). A new law is one file and one name in these lists.
// The engine chooses the law once per step (std::visit), never per pair.
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "contact/penalty_potential_law.hpp"
#include "contact/penalty_wall_law.hpp"

namespace femdem {

using BodyPairLaw = std::variant<PenaltyPotentialLaw>;
using WallLaw = std::variant<PenaltyWallLaw>;

namespace contact_laws_detail {
template <class Variant, std::size_t I = 0>
std::optional<Variant> named(std::string_view name) {
  if constexpr (I == std::variant_size_v<Variant>) {
    return std::nullopt;
  } else {
    using Law = std::variant_alternative_t<I, Variant>;
    if (name == Law::name) return Variant(std::in_place_index<I>);
    return named<Variant, I + 1>(name);
  }
}
template <class Variant>
std::vector<std::string> names() {
  std::vector<std::string> out;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (out.emplace_back(std::variant_alternative_t<I, Variant>::name), ...);
  }
  (std::make_index_sequence<std::variant_size_v<Variant>>{});
  return out;
}
}  // namespace contact_laws_detail

// The law of that name, or none.
inline std::optional<BodyPairLaw> body_pair_law_named(std::string_view name) {
  return contact_laws_detail::named<BodyPairLaw>(name);
}
inline std::optional<WallLaw> wall_law_named(std::string_view name) {
  return contact_laws_detail::named<WallLaw>(name);
}
// The law's own name (static storage) for a name it answers to.
template <class Variant>
std::string_view registered_name(std::string_view name) {
  const std::optional<Variant> law = contact_laws_detail::named<Variant>(name);
  if (!law) return {};
  return std::visit([]<class Law>(const Law&) { return std::string_view(Law::name); }, *law);
}

// Every name, in the lists' order (for the scene reader's messages).
inline std::vector<std::string> body_pair_law_names() {
  return contact_laws_detail::names<BodyPairLaw>();
}
inline std::vector<std::string> wall_law_names() {
  return contact_laws_detail::names<WallLaw>();
}

}  // namespace femdem
