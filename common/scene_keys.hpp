// The keys of a scene file as the scene reader knows them (common/scene.cpp), for checks such as
// the test that docs/scene.md documents exactly these.
#pragma once
#include <string>
#include <vector>

namespace mppm {

// Every key path the scene reader accepts, from the tables its key checks use: "time.end",
// "geometry.precracks[].box" ("[]": every entry of a list). docs/scene.md documents each.
std::vector<std::string> scene_key_paths();

}  // namespace mppm
