// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The scene reader tests (tests/io/scene/test_scene_*.cpp): a valid base scene, the same scene
// with one line replaced, and the table-driven bad-input check. Each test file lists its
// section's BadCases and runs them with
//   TEST_P(BadScene, ThrowsInputErrorNamingFileLineAndKey) { expect_bad_scene(GetParam()); }
//   INSTANTIATE_TEST_SUITE_P(SceneReader, BadScene, ::testing::ValuesIn(kBadCases), ...);
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "engine/errors.hpp"
#include "io/scene/scene_reader.hpp"

namespace femdem::test {

inline std::filesystem::path tmp_dir() {
  const std::filesystem::path d = std::filesystem::path(FEMDEM_TEST_TMP) / "scene_reader";
  std::filesystem::create_directories(d);
  return d;
}

inline std::string write_file(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path.string();
}

// A valid scene; the bad-input cases replace one of its lines (numbered from 1 in the comments)
// or append lines after its last one.
inline const std::vector<std::string> kBase = {
    R"(title = "base")",                                                                // 1
    R"([simulation])",                                                                  // 2
    R"(end_time = 1e-3)",                                                               // 3
    R"([[materials]])",                                                                 // 4
    R"(name = "steel")",                                                                // 5
    R"(model = "elastic")",                                                             // 6
    R"(density = 7800)",                                                                // 7
    R"(youngs_modulus = 200e9)",                                                        // 8
    R"(poisson_ratio = 0.3)",                                                           // 9
    R"([[bodies]])",                                                                    // 10
    R"(name = "ball")",                                                                 // 11
    R"(material = "steel")",                                                            // 12
    R"(mesh = { generator = "box", size = [0.02, 0.02, 0.02], element_size = 0.01 })",  // 13
    R"([[walls]])",                                                                     // 14
    R"(name = "floor")",                                                                // 15
    R"(normal = [0, 0, 1])",                                                            // 16
    R"([[constraints]])",                                                               // 17
    R"(body = "ball")",                                                                 // 18
    R"(fix = ["z"])",                                                                   // 19
};

// The base scene with line `line` (1-based; 0: none) replaced by `replacement` (which may hold
// several lines) and `extra` appended.
inline std::string scene_text(int line, const std::string& replacement,
                              const std::string& extra = {}) {
  std::string s;
  for (std::size_t i = 0; i < kBase.size(); ++i)
    s += (static_cast<int>(i) + 1 == line ? replacement : kBase[i]) + "\n";
  return s + extra;
}

struct BadCase {
  const char* name;  // also the scene's file name
  int line;          // line of kBase to replace (0: none)
  std::string replacement;
  std::string extra;
  std::string key;       // expected InputError::key
  int expected_line;     // expected InputError::line
  std::string contains;  // expected part of the message
};

inline void PrintTo(const BadCase& c, std::ostream* os) {
  *os << c.name;
}

class BadScene : public ::testing::TestWithParam<BadCase> {};

// The body of BadScene.ThrowsInputErrorNamingFileLineAndKey for one case.
inline void expect_bad_scene(const BadCase& c) {
  const std::string path = write_file(tmp_dir() / "bad" / (std::string(c.name) + ".toml"),
                                      scene_text(c.line, c.replacement, c.extra));
  try {
    load_scene(path);
    FAIL() << "no InputError for case " << c.name;
  } catch (const InputError& e) {
    SCOPED_TRACE(e.describe());
    EXPECT_EQ(e.key, c.key);
    EXPECT_EQ(e.file, path);
    EXPECT_EQ(e.line, c.expected_line);
    if (e.line > 0) {
      EXPECT_GT(e.column, 0);
    }
    EXPECT_NE(std::string(e.what()).find(c.contains), std::string::npos) << e.what();
    // describe() reads "file:line:col: key: message"
    EXPECT_EQ(e.describe().rfind(path + ":" + std::to_string(c.expected_line) + ":", 0), 0u);
  } catch (const std::exception& e) {
    FAIL() << "wrong exception type for case " << c.name << ": " << e.what();
  }
}

}  // namespace femdem::test
