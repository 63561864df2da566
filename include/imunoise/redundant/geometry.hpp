#pragma once
// The sensing axes of a redundant gyro unit: n unit vectors h_i in the body frame, the rows of
// the n x 3 measurement matrix H of m = H w + noise (docs/redundant.md).
//
// Built-in geometries (a cone's axis is body z; azimuth from body x towards y):
//   tetra      4 axes on a cone of half-angle atan(sqrt 2) = 54.7356 deg at azimuths 0, 90, 180,
//              270 deg: H^T H = (4/3) I, per-axis gain sqrt(3/4) = 0.8660, GDOP 1.500;
//   cone:N:DEG N axes on a cone of half-angle DEG, azimuths 360 (i-1)/N deg;
//   3+1        the orthogonal triad plus (1,1,1)/sqrt 3: gain sqrt(5/6) = 0.9129, GDOP 1.581;
//   dodeca     six axes normal to the faces of a regular dodecahedron (the icosahedron's
//              vertex directions (0, +-1, phi) and cyclic): H^T H = 2 I, gain 0.7071, GDOP 1.2247;
//   triads:K   K co-aligned orthogonal triads (a flight controller's K IMUs): x, y, z of triad 1,
//              then of triad 2, ... (the order of a PX4 log's instances gyro0_x .. gyroK_z);
//   FILE       YAML or CSV/text of unit vectors x,y,z or azimuth_deg,elevation_deg pairs
//              (elevation from the body x-y plane); see read_geometry_file.
// Every geometry is checked: at least 3 axes, no zero-length axis, and the axes span 3-D
// (the smallest eigenvalue of H^T H is at least 1e-9 of the largest), else InputError.
#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace imunoise::redundant {

using Axis = std::array<double, 3>;

/// A small dense row-major matrix (the module's public headers carry no Eigen types).
struct Matrix {
  std::size_t rows = 0;
  std::size_t cols = 0;
  std::vector<double> values;  ///< rows * cols, row-major

  Matrix() = default;
  Matrix(std::size_t r, std::size_t c) : rows(r), cols(c), values(r * c, 0.0) {}
  double& operator()(std::size_t r, std::size_t c) { return values[r * cols + c]; }
  double operator()(std::size_t r, std::size_t c) const { return values[r * cols + c]; }
};

struct Geometry {
  std::string name;                ///< "tetra", "cone:6:54.7356", "3+1", "dodeca" or the file name
  std::vector<Axis> axes;          ///< unit sensing axes in the body frame, one per sensor
  std::vector<std::string> notes;  ///< what was done to the input (normalised vectors, ...)

  [[nodiscard]] std::size_t size() const { return axes.size(); }
};

/// The cone half-angle of the isotropic tetrahedral cone, atan(sqrt 2) (deg).
inline constexpr double kTetraHalfAngleDeg = 54.735610317245346;

/// N axes on a cone of half-angle `half_angle_deg` (0 < angle < 180) about body z, azimuths
/// 360 (i - 1) / N deg. InputError for N < 3 or a bad angle (0 or 180 deg: all axes parallel).
Geometry cone_geometry(std::size_t n, double half_angle_deg);

/// "tetra", "cone:N:DEG", "3+1", "dodeca", "triads:K" (1 <= K <= 64), or a path to a geometry
/// file (read_geometry_file).
/// InputError naming the text and the forms accepted.
Geometry make_geometry(std::string_view spec);

/// Checks and normalises user axes: non-unit vectors are normalised (a note says so), a
/// zero-length or non-finite one is refused naming it (1-based, "axis 3 of FILE"), fewer
/// than 3 axes or axes that do not span 3-D (coplanar, collinear) are refused.
Geometry geometry_from_axes(std::string name, std::vector<Axis> axes);

/// Reads a geometry file.
///  - YAML (.yaml/.yml): a map with `axes: [[x, y, z], ...]` (unit vectors) or
///    `azimuth_elevation_deg: [[az, el], ...]`, or a bare sequence of 3- or 2-element rows.
///  - Anything else is text: one axis per line, fields separated by commas, semicolons, tabs or
///    blanks; '#' starts a comment; one optional header line. Every row has 3 fields (x, y, z)
///    or every row has 2 (azimuth_deg, elevation_deg).
/// Another number of fields, a non-number, or a mix of 2 and 3 is an InputError naming the
/// file and line.
Geometry read_geometry_file(const std::filesystem::path& path);

/// The unit vector of azimuth `az_deg` (from x towards y) and elevation `el_deg` (from the
/// x-y plane towards +z).
Axis axis_from_azimuth_elevation(double az_deg, double el_deg);

/// The n x 3 measurement matrix (rows = axes).
Matrix measurement_matrix(const Geometry& geometry);

}  // namespace imunoise::redundant
