// Curved 3-D CAD part (OpenCASCADE), in MILLIMETRES: a sphere of radius 6 bored through along
// z by a hole of radius 2 (a "napkin ring": curved everywhere, no face along the lattice).
// Volume = pi/6 h^3 with h = 2 sqrt(6^2 - 2^2): 758.30 mm^3. Exported to bored_sphere.step with
// `gmsh bored_sphere.geo -0 -o bored_sphere.step`.
SetFactory("OpenCASCADE");
Sphere(1) = {0, 0, 0, 6};
Cylinder(2) = {0, 0, -7, 0, 0, 14, 2};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
