// SPDX-License-Identifier: GPL-3.0-or-later
#include "tools/femdem/run/plot_script.hpp"

#include <sys/wait.h>

#include <cstdlib>

namespace femdem {
namespace {

std::string shell_quote(const std::string& s) {  // '...' with each ' written as '\''
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

std::string find_plot_script(const std::string& exe, const char* name) {
  namespace fs = std::filesystem;
  std::error_code ec;
#ifdef FEMDEM_TOOLS_DIR
  if (fs::exists(fs::path(FEMDEM_TOOLS_DIR) / name, ec))
    return (fs::path(FEMDEM_TOOLS_DIR) / name).string();
#endif
  // beside a build in the source tree, or installed (cmake --install: PREFIX/bin/femdem and
  // PREFIX/share/femdem/tools)
  for (const char* dir : {"../tools", "../share/femdem/tools"}) {
    const fs::path near = fs::path(exe).parent_path() / dir / name;
    if (fs::exists(near, ec)) return near.string();
  }
  return {};
}

int run_plot_script(const std::string& script, const std::filesystem::path& out_dir,
                    const std::filesystem::path& log_file) {
  int code = 127;
  for (const char* python : {"/usr/bin/python3", "python3"}) {
    if (python[0] == '/' && !std::filesystem::exists(python)) continue;
    const std::string cmd = std::string(python) + " " + shell_quote(script) + " " +
                            shell_quote(out_dir.string()) + " >> " +
                            shell_quote(log_file.string()) + " 2>&1";
    const int status = std::system(cmd.c_str());
    code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : 127;
    if (code != 127) break;
  }
  return code;
}

}  // namespace femdem
