// The mid-thickness layer (mid_thickness_layer.hpp).
#include "postprocess/mid_thickness_layer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mppm::post {

MidThicknessLayer mid_thickness_layer(const std::vector<double>& z, const std::vector<char>& body, double spacing) {
  if (z.size() != body.size()) throw std::invalid_argument("mid_thickness_layer: arrays of different lengths");
  if (!(spacing > 0)) throw std::invalid_argument("mid_thickness_layer: the spacing must be positive");
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (std::size_t i = 0; i < z.size(); ++i)
    if (body[i]) low = std::min(low, z[i]), high = std::max(high, z[i]);
  if (!(low <= high)) throw std::invalid_argument("mid_thickness_layer: no body point");
  const double middle = 0.5 * (low + high);
  // The plane nearest the middle; coordinates within dx/4 of each other count as one plane (the
  // rounding of the lattice), and of two planes equally near (an even number of planes) the lower.
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < z.size(); ++i)
    if (body[i]) nearest = std::min(nearest, std::fabs(z[i] - middle));
  MidThicknessLayer layer;
  layer.z = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < z.size(); ++i)
    if (body[i] && std::fabs(z[i] - middle) <= nearest + 0.25 * spacing) layer.z = std::min(layer.z, z[i]);
  layer.include.assign(z.size(), 0);
  for (std::size_t i = 0; i < z.size(); ++i)
    if (body[i] && std::fabs(z[i] - layer.z) <= 0.25 * spacing) {
      layer.include[i] = 1;
      ++layer.points;
    }
  layer.flat_z.assign(z.size(), layer.z);
  return layer;
}

}  // namespace mppm::post
