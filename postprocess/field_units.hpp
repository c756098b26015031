// Units of the snapshot fields and derived arrays, for figure colour bars and the README.
#pragma once
#include <string>

namespace mppm::post {

// "m", "rad", "Pa", "-", ... ; "" for a field this table does not know.
std::string field_unit(const std::string& name);

}  // namespace mppm::post
