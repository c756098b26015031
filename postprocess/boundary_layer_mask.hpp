// Which points are "away from the boundary layers": body points (region 0) farther than a
// margin from every layer point (region > 0) and every loaded body point (boundary_id > 0).
// Plastic strain concentrates where plates and pressures act; the shear-band metrics must
// not mistake that for a band.
#pragma once
#include <cstdint>
#include <vector>

namespace mppm::post {

std::vector<char> points_away_from_boundaries(const std::vector<double>& x, const std::vector<double>& y,
                                              const std::vector<double>& z, const std::vector<int>& region,
                                              const std::vector<int>& boundary_id, double margin);

}  // namespace mppm::post
