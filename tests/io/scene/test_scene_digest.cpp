// SPDX-License-Identifier: GPL-3.0-or-later
// The scene digest that ties a checkpoint to its scene: the same whatever the settings a resume
// may change, different for any other change; the resumable settings read back as overrides.
#include "io/scene/scene_digest.hpp"

#include <gtest/gtest.h>

namespace femdem {
namespace {

const char* const kScene = R"(title = "t"

[simulation]
end_time = 0.001
output_interval = 2e-05
history_interval = 1e-06
checkpoint_interval = 0.0
checkpoint_wall_interval = 600.0
threads = 0
contact_time_step_safety = 0.5

[[materials]]
name = "steel"
model = "elastic"
density = 7850.0
)";

std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(SceneDigest, IgnoresWhatAResumeMayChangeAndSeesEverythingElse) {
  const std::string d = scene_digest(kScene);
  EXPECT_EQ(d.size(), 16u);
  EXPECT_EQ(scene_digest(with(kScene, "end_time = 0.001", "end_time = 0.5")), d);
  EXPECT_EQ(scene_digest(with(kScene, "threads = 0", "threads = 3")), d);
  EXPECT_EQ(scene_digest(with(kScene, "output_interval = 2e-05", "output_interval = 1e-3")), d);
  // a run resumed with other contact safety computes the rest with it; so does a checkpoint
  // written before the key existed (its resolved scene has no such line)
  EXPECT_EQ(scene_digest(
                with(kScene, "contact_time_step_safety = 0.5", "contact_time_step_safety = 0.8")),
            d);
  EXPECT_EQ(scene_digest(with(kScene, "contact_time_step_safety = 0.5\n", "")), d);
  EXPECT_NE(scene_digest(with(kScene, "density = 7850.0", "density = 7851.0")), d);
  EXPECT_NE(scene_digest(with(kScene, "title = \"t\"", "title = \"u\"")), d);
  EXPECT_EQ(first_differing_line(scene_identity_text(kScene),
                                 scene_identity_text(with(kScene, "7850.0", "7851.0"))),
            "density = 7850.0");
}

TEST(SceneDigest, ResumableSettingsAreOverridesThatReadBackExactly) {
  const std::vector<std::string> s = resumable_settings(kScene);
  const std::vector<std::string> expected = {"simulation.end_time=0.001",
                                             "simulation.output_interval=2e-05",
                                             "simulation.history_interval=1e-06",
                                             "simulation.checkpoint_interval=0.0",
                                             "simulation.checkpoint_wall_interval=600.0",
                                             "simulation.threads=0",
                                             "simulation.contact_time_step_safety=0.5"};
  EXPECT_EQ(s, expected);
}

}  // namespace
}  // namespace femdem
