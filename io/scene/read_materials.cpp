// SPDX-License-Identifier: GPL-3.0-or-later
// [[materials]]: the common constants here, each model's own keys read by the model itself
// (materials/material_registry.hpp) through the MaterialKeys view of the entry below.
#include <set>

#include "io/scene/toml_reader.hpp"
#include "materials/material_params.hpp"

namespace femdem::scene {

// A [[materials]] entry as the model readers see it (materials/material_keys.hpp): the
// Reader's checks and messages, the values recorded into the entry's resolved table.
class Reader::MaterialTable final : public MaterialKeys {
 public:
  MaterialTable(const Reader& r, const toml::table& t, const std::string& prefix, toml::table& out)
      : r_(r), t_(t), p_(prefix), out_(out) {}
  bool has(std::string_view key) const override { return t_.contains(key); }
  double number(std::string_view key, std::optional<double> fallback) override {
    return r_.number(t_, key, p_, fallback, &t_);
  }
  double positive(std::string_view key, std::optional<double> fallback) override {
    return r_.positive(t_, key, p_, fallback, &t_);
  }
  std::optional<std::string> text(std::string_view key) override {
    return r_.opt_string(t_, key, p_);
  }
  std::vector<std::pair<double, double>> pairs(std::string_view key, const std::string& what_array,
                                               const std::string& what_pair) override {
    const toml::node* n = t_.get(key);
    const toml::array* arr = n ? n->as_array() : nullptr;
    if (!arr || arr->empty()) fail(key, what_array);
    std::vector<std::pair<double, double>> out;
    for (const toml::node& pt : *arr) {
      const toml::array* pair = pt.as_array();
      if (!pair || pair->size() != 2 || !(*pair)[0].is_number() || !(*pair)[1].is_number())
        r_.fail(&pt, dotted(p_, key), what_pair);
      out.emplace_back((*pair)[0].value<double>().value(), (*pair)[1].value<double>().value());
    }
    return out;
  }
  void record(std::string_view key, double value) override { out_.insert_or_assign(key, value); }
  void record(std::string_view key, const std::string& value) override {
    out_.insert_or_assign(key, value);
  }
  void record(std::string_view key, const std::vector<std::pair<double, double>>& v) override {
    toml::array a;
    for (const auto& [x, y] : v) a.push_back(toml::array{x, y});
    out_.insert_or_assign(key, std::move(a));
  }
  [[noreturn]] void fail(std::string_view key, const std::string& message) const override {
    const toml::node* n = t_.get(key);
    r_.fail(n ? n : &t_, dotted(p_, key), message);
  }
  [[noreturn]] void fail_entry(const std::string& message) const override {
    r_.fail(&t_, p_, message);
  }
  std::string did_you_mean(std::string_view word,
                           const std::vector<std::string>& candidates) const override {
    return scene::did_you_mean(word, candidates);
  }

 private:
  const Reader& r_;
  const toml::table& t_;
  const std::string& p_;
  toml::table& out_;
};

// The model comes first (it decides which keys are allowed), then the common constants, then
// the model's own keys, read by the model (materials/material_registry.hpp).
void Reader::read_materials(const toml::table& root, ModelSpec& spec, toml::array& out) const {
  const std::vector<std::string> models = material_model_names();
  std::set<std::string> names;
  for (const auto& [tp, p] : entries(root, "materials")) {
    const toml::table& t = *tp;
    const std::string model = string(t, "model", p, &t);
    const int index = material_model_index(model);
    if (index < 0)
      fail(t.get("model"), dotted(p, "model"),
           "unknown material model '" + model + "'" + did_you_mean(model, models) +
               "; available: " + join(models));
    std::vector<std::string> keys = {"name", "model", "density", "youngs_modulus", "poisson_ratio"};
    with_material_model(static_cast<std::size_t>(index), [&](auto m) {
      for (std::string& k : decltype(m)::keys()) keys.push_back(std::move(k));
    });
    check_keys(t, p, keys, "for model '" + model + "'");
    MaterialParams m;
    m.name = entry_name(t, p, names, "material");
    m.density = positive(t, "density", p, std::nullopt, &t);
    m.youngs_modulus = positive(t, "youngs_modulus", p, std::nullopt, &t);
    m.poisson_ratio = number(t, "poisson_ratio", p, std::nullopt, &t);
    if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
      fail(t.get("poisson_ratio"), dotted(p, "poisson_ratio"),
           "must lie in (-1, 0.5), got " + format_number(m.poisson_ratio));
    toml::table o;
    o.insert_or_assign("name", m.name);
    o.insert_or_assign("model", model);
    o.insert_or_assign("density", m.density);
    o.insert_or_assign("youngs_modulus", m.youngs_modulus);
    o.insert_or_assign("poisson_ratio", m.poisson_ratio);
    MaterialTable keys_of_model(*this, t, p, o);
    with_material_model(static_cast<std::size_t>(index), [&](auto model_type) {
      using Model = decltype(model_type);
      m.model = Model::read(m, keys_of_model);
    });
    spec.materials.push_back(m);
    out.push_back(std::move(o));
  }
}

}  // namespace femdem::scene
