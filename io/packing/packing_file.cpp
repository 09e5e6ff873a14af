// SPDX-License-Identifier: GPL-3.0-or-later
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "engine/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/packing/packing.hpp"
#include "io/packing/packing_internal.hpp"

namespace femdem {

using packing_detail::num;

// ---------------------------------------------------------------------------------------------
// Files

std::string packing_file_text(const Packing& packing) {
  std::ostringstream os;
  const PackingStats& s = packing.stats;
  os << "# femdem packing, format 1 (docs/OUTPUTS.md, \"Packing files\")\n";
  os << "# [generator]\n";
  os << "# program = \"" << (packing.generator.empty() ? "unknown" : packing.generator) << "\"\n";
  if (!packing.params_text.empty()) {
    os << "# [parameters]\n";
    std::istringstream in(packing.params_text);
    for (std::string line; std::getline(in, line);) os << "# " << line << "\n";
  }
  os << "# [result]\n";
  os << "# count = " << packing.particles.size() << "\n";
  os << "# particle_volume = " << num(s.particle_volume) << "\n";
  os << "# bed_height = " << num(s.bed_height) << "\n";
  os << "# packing_fraction = " << num(s.packing_fraction) << "\n";
  os << "# container_fraction = " << num(s.container_fraction) << "\n";
  if (std::isfinite(s.core_packing_fraction))
    os << "# core_packing_fraction = " << num(s.core_packing_fraction) << "\n";
  if (std::isfinite(s.min_gap)) os << "# min_gap = " << num(s.min_gap) << "\n";
  if (s.settle_steps > 0) {
    os << "# settle_time = " << num(s.settle_time) << "\n";
    os << "# settle_steps = " << s.settle_steps << "\n";
    os << "# max_speed = " << num(s.max_speed) << "\n";
    os << "# at_rest = " << (s.at_rest ? "true" : "false") << "\n";
  }
  os << "id,shape,x,y,z,radius,qw,qx,qy,qz\n";
  char buf[512];
  for (std::size_t i = 0; i < packing.particles.size(); ++i) {
    const PackedParticle& q = packing.particles[i];
    std::snprintf(buf, sizeof buf, "%zu,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                  i + 1, q.shape.c_str(), q.centre.x(), q.centre.y(), q.centre.z(), q.radius,
                  q.orientation.w(), q.orientation.x(), q.orientation.y(), q.orientation.z());
    os << buf;
  }
  return os.str();
}

void write_packing(const std::string& path, const Packing& packing) {
  write_file_atomically(path, packing_file_text(packing), false);
}

Packing read_packing(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read the packing file", path);
  Packing packing;
  std::string section, line;
  bool have_columns = false;
  int lineno = 0;
  const std::string columns = "id,shape,x,y,z,radius,qw,qx,qy,qz";
  auto fail = [&](const std::string& msg, int column = 0) {
    throw InputError(msg, path, lineno, column);
  };
  auto header_value = [](const std::string& s) {
    std::string v = s.substr(s.find('=') + 1);
    v.erase(0, v.find_first_not_of(' '));
    if (v.size() >= 2 && v.front() == '"') v = v.substr(1, v.size() - 2);
    return v;
  };
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (have_columns) continue;
      std::string body = line.substr(1);
      if (!body.empty() && body[0] == ' ') body.erase(0, 1);
      if (!body.empty() && body[0] == '[') {
        section = body;
      } else if (section == "[parameters]") {
        packing.params_text += body + "\n";
      } else if (section == "[generator]" && body.rfind("program", 0) == 0) {
        packing.generator = header_value(body);
      }
      continue;
    }
    if (!have_columns) {
      if (line != columns)
        fail("expected the column line '" + columns + "' before the rows, got '" + line + "'", 1);
      have_columns = true;
      continue;
    }
    // id,shape,x,y,z,radius,qw,qx,qy,qz
    std::vector<std::string> fields;
    std::vector<int> starts;
    std::size_t b = 0;
    while (true) {
      const std::size_t e = line.find(',', b);
      starts.push_back(static_cast<int>(b) + 1);
      fields.push_back(line.substr(b, e == std::string::npos ? std::string::npos : e - b));
      if (e == std::string::npos) break;
      b = e + 1;
    }
    if (fields.size() != 10)
      fail("expected 10 fields (" + columns + "), got " + std::to_string(fields.size()), 1);
    double v[8];
    for (int k = 0; k < 8; ++k) {
      const std::string& f = fields[static_cast<std::size_t>(k) + 2];
      const char* first = f.data();
      const auto r = std::from_chars(first, first + f.size(), v[k]);
      if (r.ec != std::errc() || r.ptr != first + f.size() || !std::isfinite(v[k]))
        fail("field '" + f + "' is not a finite number", starts[static_cast<std::size_t>(k) + 2]);
    }
    PackedParticle q;
    q.shape = fields[1];
    if (q.shape.empty()) fail("empty shape name", starts[1]);
    q.centre = Vec3(v[0], v[1], v[2]);
    q.radius = v[3];
    if (!(q.radius > 0.0)) fail("the radius must be positive", starts[5]);
    q.orientation = Eigen::Quaterniond(v[4], v[5], v[6], v[7]);
    const double norm = q.orientation.norm();
    if (!(std::abs(norm - 1.0) < 1e-6))
      fail("the quaternion (qw, qx, qy, qz) must have unit length, has " + num(norm), starts[6]);
    q.orientation.normalize();
    packing.particles.push_back(std::move(q));
  }
  if (!have_columns) throw InputError("no column line '" + columns + "' in the file", path);
  if (packing.particles.empty()) throw InputError("the packing has no particles", path);
  return packing;
}

}  // namespace femdem
