// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/results/summary_writer.hpp"

#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"

namespace femdem {

namespace {

using Json = nlohmann::ordered_json;

Json vec3(const std::array<double, 3>& v) {
  return Json::array({v[0], v[1], v[2]});
}

}  // namespace

const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::completed:
      return "completed";
    case RunStatus::unstable:
      return "unstable";
    case RunStatus::interrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string summary_to_json(const RunSummary& s) {
  Json j;
  j["scene"] = s.scene;
  j["status"] = to_string(s.status);
  j["end_time"] = s.end_time;
  j["steps"] = s.steps;
  j["time_step"] = s.time_step;
  j["wall_time_s"] = s.wall_time_s;
  j["threads"] = s.threads;
  j["nodes"] = s.nodes;
  j["elements"] = s.elements;
  j["energy"] = Json{{"kinetic", s.energy.kinetic},
                     {"internal", s.energy.internal},
                     {"plastic_dissipation", s.energy.plastic_dissipation},
                     {"contact", s.energy.contact},
                     {"contact_dissipation", s.energy.contact_dissipation},
                     {"viscous_dissipation", s.energy.viscous_dissipation},
                     {"mass_scaling_dissipation", s.energy.mass_scaling_dissipation},
                     {"external_work", s.energy.external_work},
                     {"balance_error", s.energy.balance_error}};
  Json bodies = Json::object();
  for (const BodySummary& b : s.bodies) {
    Json jb;
    jb["mass"] = b.mass;
    jb["added_mass"] = b.added_mass;
    jb["volume"] = b.volume;
    jb["com"] = vec3(b.com);
    jb["vcom"] = vec3(b.vcom);
    jb["angular_velocity"] = vec3(b.angular_velocity);
    jb["kinetic_energy"] = b.kinetic_energy;
    jb["bbox_min"] = vec3(b.bbox_min);
    jb["bbox_max"] = vec3(b.bbox_max);
    jb["max_equivalent_plastic_strain"] = b.max_equivalent_plastic_strain;
    jb["max_principal_stress"] = b.max_principal_stress;
    jb["max_principal_stress_time"] = b.max_principal_stress_time;
    if (b.coefficient_of_restitution) {
      jb["coefficient_of_restitution"] =
          Json{{"com", b.coefficient_of_restitution->com},
               {"kinetic_energy", b.coefficient_of_restitution->kinetic_energy}};
    } else {
      jb["coefficient_of_restitution"] = nullptr;
    }
    bodies[b.name] = std::move(jb);
  }
  j["bodies"] = std::move(bodies);
  Json extra = Json::object();
  for (const auto& [key, value] : s.extra) extra[key] = value;
  j["extra"] = std::move(extra);
  if (s.compaction) {
    Json c = Json::object();
    for (const auto& [key, value] : s.compaction->values) c[key] = value;
    Json h = Json::object(), k = Json::object();
    for (const auto& [key, value] : s.compaction->heckel) h[key] = value;
    for (const auto& [key, value] : s.compaction->kawakita) k[key] = value;
    c["heckel"] = std::move(h);
    c["kawakita"] = std::move(k);
    j["compaction"] = std::move(c);
  }
  // Invalid UTF-8 in a name is replaced rather than thrown on: the summary must get written.
  return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

void write_summary(const std::filesystem::path& path, const RunSummary& summary) {
  write_file_atomically(path, summary_to_json(summary), /*durable=*/true);
}

}  // namespace femdem
