// Shear-band metrics of docs/stages.md "Metrics": the inclination of each band to the x axis and the
// band width, measured from the equivalent plastic shear strain field of a 2-D run.
// A pure function on plain arrays, so the tests can validate it on synthetic fields.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace mppm::post {

struct ShearBandSettings {
  double spacing = 0.0;                  // lattice spacing dx [m]: Hough offset bin, profile bins
  double threshold_fraction = 0.5;       // band points: strain >= fraction * max (half maximum)
  double min_separation_deg = 30.0;      // a second band must differ this much in direction
  double second_band_ratio = 0.3;        // ... and collect this share of the first band's weight
                                         // from points the first band does not explain
  double max_band_area_fraction = 0.5;   // more points above threshold = no localization
  double profile_window_fraction = 0.4;  // half-window of the width profile / smaller extent
};

struct ShearBand {
  double angle_deg = 0.0;                 // acute angle between band and x axis, [0, 90]
  double direction_deg = 0.0;             // direction of the band line, [0, 180)
  double centre_x = 0.0, centre_y = 0.0;  // a point on the band centre line [m]
  std::optional<double> width_m;          // full width at half maximum of the strain profile
  std::size_t points = 0;                 // points above threshold assigned to the band
};

struct ShearBandResult {
  std::vector<ShearBand> bands;  // strongest first; empty if no localization
  std::optional<double> mean_angle_deg;
  std::optional<double> mean_width_m;
  std::string note;  // why no band (or only one) was found
};

// x, y: point positions [m]; strain: equivalent plastic shear strain per point; include:
// nonzero for the points to use (the body away from boundary layers). All of equal length.
ShearBandResult measure_shear_bands(const std::vector<double>& x, const std::vector<double>& y,
                                    const std::vector<double>& strain, const std::vector<char>& include,
                                    const ShearBandSettings& settings);

}  // namespace mppm::post
