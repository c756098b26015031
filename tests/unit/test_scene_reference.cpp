// docs/scene.md and the scene reader agree: every key the reader accepts is documented, and every
// documented key is one the reader accepts. The reader's keys come from the tables its own key
// checks use (scene_key_paths); the documented ones from the first column of the doc's tables.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <string>

#include "common/scene_keys.hpp"

using namespace mppm;

namespace {

// The first cell of every table row "| `key.path` | ..." of the file.
std::set<std::string> documented_keys(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::set<std::string> keys;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    const auto end = line.find('`', 3);
    if (end == std::string::npos) continue;
    keys.insert(line.substr(3, end - 3));
  }
  return keys;
}

}  // namespace

TEST(SceneReference, DocumentsExactlyTheKeysTheReaderAccepts) {
  const std::string doc = std::string(MPPM_SOURCE_DIR) + "/docs/scene.md";
  const std::set<std::string> documented = documented_keys(doc);
  const auto accepted_list = scene_key_paths();
  const std::set<std::string> accepted(accepted_list.begin(), accepted_list.end());
  ASSERT_GT(accepted.size(), 50u);
  for (const auto& key : accepted) {
    EXPECT_TRUE(documented.count(key)) << "the scene reader accepts " << key << ", which " << doc
                                       << " does not document";
  }
  for (const auto& key : documented) {
    EXPECT_TRUE(accepted.count(key)) << doc << " documents " << key << ", which the scene reader does not accept";
  }
}
