// SPDX-License-Identifier: GPL-3.0-or-later
// [output]: what results.h5 holds beyond the default fields (docs/SCENES.md, "[output]").
#include <algorithm>

#include "engine/output_fields.hpp"
#include "io/scene/toml_reader.hpp"

namespace femdem::scene {

void Reader::read_output(const toml::table& root, ModelSpec& spec, toml::table& out) const {
  toml::array fields_out;
  if (const toml::node* n = root.get("output")) {
    const toml::table& t = require_table(n, "output");
    check_keys(t, "output", {"fields"});
    if (const toml::node* f = t.get("fields")) {
      const toml::array* a = f->as_array();
      if (!a)
        fail(f, "output.fields",
             "expected an array of field names, e.g. [\"log_strain\", \"contact_pressure\"]");
      std::vector<std::string> chosen;
      for (const auto& e : *a) {
        const std::string name = e.is_string() ? e.as_string()->get() : std::string();
        const auto& known = kOptionalOutputFields;
        if (std::find(known.begin(), known.end(), name) == known.end())
          fail(&e, "output.fields",
               (e.is_string() ? "unknown field '" + name + "'" + did_you_mean(name, known)
                              : "expected a field name, got " + type_name(e)) +
                   "; optional fields: " + join(known));
        if (std::find(chosen.begin(), chosen.end(), name) != chosen.end())
          fail(&e, "output.fields", "field '" + name + "' is listed twice");
        chosen.push_back(name);
      }
      // results.h5 lists them in one order whatever the scene's
      for (const std::string& k : kOptionalOutputFields)
        if (std::find(chosen.begin(), chosen.end(), k) != chosen.end()) {
          spec.simulation.output_fields.push_back(k);
          fields_out.push_back(k);
        }
    }
  }
  out.insert_or_assign("fields", std::move(fields_out));
}

}  // namespace femdem::scene
