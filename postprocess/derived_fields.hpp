// Invariants derived from the tensors a run wrote, so ParaView users can colour by a scalar:
// von Mises and mean stress of `stress`, magnitude of `couple_stress`. Plain arrays in, plain
// arrays out; each point writes only its own value (thread-count independent).
#pragma once
#include <vector>

namespace mppm::post {

// stress: 9 components per point, row-major 3x3 (2-D runs embed the plane-strain state).
// The Cosserat stress is not symmetric; von Mises is taken of its symmetric part:
// q = sqrt(3/2 s:s), s = sym(sigma) - p 1, p = tr(sigma)/3.
std::vector<double> von_mises_stress(const std::vector<double>& stress);
std::vector<double> mean_stress(const std::vector<double>& stress);

// Euclidean norm of each point's `components` values.
std::vector<double> magnitude(const std::vector<double>& data, int components);

}  // namespace mppm::post
