#include "imunoise/redundant/geometry.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <Eigen/Dense>
#include <fmt/core.h>
#include <yaml-cpp/yaml.h>

#include "imunoise/error.hpp"
#include "imunoise/io/text_reader.hpp"

namespace imunoise::redundant {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
// A unit vector is "unit" to this relative tolerance (a file with 6 printed digits is).
constexpr double kUnitTolerance = 1e-6;
// Axes span 3-D when the smallest eigenvalue of H^T H is at least this fraction of the largest.
constexpr double kSpanTolerance = 1e-9;

const char* kForms =
    "use tetra, cone:N:DEG (e.g. cone:6:54.7356), 3+1, dodeca, triads:K (K co-aligned triads), or a "
    "YAML/CSV file of unit "
    "vectors (x,y,z) or azimuth,elevation pairs in degrees";

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

double number_or_throw(std::string_view text, const std::string& what) {
  const auto v = io::parse_number(trim(text));
  if (!v || !std::isfinite(*v)) {
    throw InputError(what + ": '" + std::string(text) + "' is not a finite number; " + kForms);
  }
  return *v;
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  char sep = 0;
  if (line.find(',') != std::string::npos) sep = ',';
  else if (line.find(';') != std::string::npos) sep = ';';
  if (sep != 0) {
    std::stringstream in(line);
    std::string field;
    while (std::getline(in, field, sep)) fields.push_back(trim(field));
    if (!line.empty() && line.back() == sep) fields.emplace_back();
    return fields;
  }
  std::stringstream in(line);
  std::string field;
  while (in >> field) fields.push_back(field);
  return fields;
}

Geometry from_rows(const std::string& source, const std::vector<std::vector<double>>& rows,
                   const std::vector<std::size_t>& lines) {
  std::vector<Axis> axes;
  bool pairs = false;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto& row = rows[r];
    const std::string where = lines.empty() ? fmt::format("{}: row {}", source, r + 1)
                                            : fmt::format("{}:{}", source, lines[r]);
    if (row.size() != 2 && row.size() != 3) {
      throw InputError(fmt::format("{}: {} fields; a geometry row has 3 (x, y, z of a sensing "
                                   "axis) or 2 (azimuth_deg, elevation_deg)", where, row.size()));
    }
    if (r == 0) pairs = row.size() == 2;
    if ((row.size() == 2) != pairs) {
      throw InputError(fmt::format("{}: {} fields but the first row has {}; use x,y,z rows or "
                                   "azimuth,elevation rows throughout", where, row.size(),
                                   pairs ? 2 : 3));
    }
    axes.push_back(pairs ? axis_from_azimuth_elevation(row[0], row[1])
                         : Axis{row[0], row[1], row[2]});
  }
  Geometry g = geometry_from_axes(source, std::move(axes));
  if (pairs) g.notes.insert(g.notes.begin(), "axes given as azimuth/elevation pairs (deg)");
  return g;
}

Geometry read_yaml(const std::filesystem::path& path) {
  const std::string source = path.string();
  YAML::Node root;
  try {
    root = YAML::LoadFile(source);
  } catch (const YAML::Exception& e) {
    throw InputError(source + ": not valid YAML (" + e.what() + "); " + kForms);
  }
  YAML::Node list;
  bool pairs_key = false;
  if (root.IsSequence()) {
    list = root;
  } else if (root.IsMap() && root["axes"]) {
    list = root["axes"];
  } else if (root.IsMap() && root["azimuth_elevation_deg"]) {
    list = root["azimuth_elevation_deg"];
    pairs_key = true;
  } else {
    throw InputError(source + ": no 'axes' or 'azimuth_elevation_deg' list; write axes: "
                              "[[x, y, z], ...] or azimuth_elevation_deg: [[az, el], ...]");
  }
  if (!list.IsSequence()) throw InputError(source + ": the axes must be a list of rows");
  std::vector<std::vector<double>> rows;
  for (std::size_t r = 0; r < list.size(); ++r) {
    const YAML::Node row = list[r];
    const std::size_t line = static_cast<std::size_t>(row.Mark().line + 1);
    if (!row.IsSequence()) {
      throw InputError(fmt::format("{}:{}: axis {} is not a list of numbers; write [x, y, z] or "
                                   "[azimuth_deg, elevation_deg]", source, line, r + 1));
    }
    std::vector<double> values;
    for (std::size_t c = 0; c < row.size(); ++c) {
      values.push_back(number_or_throw(row[c].Scalar(),
                                       fmt::format("{}:{}: axis {}", source, line, r + 1)));
    }
    if (pairs_key && values.size() != 2) {
      throw InputError(fmt::format("{}:{}: {} fields under azimuth_elevation_deg; write "
                                   "[azimuth_deg, elevation_deg]", source, line, values.size()));
    }
    if (!pairs_key && root.IsMap() && values.size() != 3) {
      throw InputError(fmt::format("{}:{}: {} fields under axes; write [x, y, z] (or use "
                                   "azimuth_elevation_deg for pairs)", source, line, values.size()));
    }
    rows.push_back(std::move(values));
  }
  std::vector<std::size_t> lines;
  for (std::size_t r = 0; r < list.size(); ++r) lines.push_back(static_cast<std::size_t>(list[r].Mark().line + 1));
  return from_rows(source, rows, lines);
}

Geometry read_text(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::ifstream in(path);
  if (!in) throw InputError(source + ": cannot open the geometry file; check the path");
  std::vector<std::vector<double>> rows;
  std::vector<std::size_t> lines;
  std::string line;
  std::size_t number = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    line = trim(line);
    if (line.empty()) continue;
    const auto fields = split_fields(line);
    std::vector<double> values;
    bool numeric = true;
    for (const auto& f : fields) {
      const auto v = io::parse_number(f);
      if (!v) {
        numeric = false;
        break;
      }
      values.push_back(*v);
    }
    if (!numeric) {
      if (rows.empty() && !header_seen) {
        header_seen = true;  // one header line, e.g. "x,y,z" or "azimuth_deg,elevation_deg"
        continue;
      }
      throw InputError(fmt::format("{}:{}: '{}' is not a row of numbers; a geometry file has "
                                   "rows x,y,z or azimuth_deg,elevation_deg", source, number, line));
    }
    for (const double v : values) {
      if (!std::isfinite(v)) {
        throw InputError(fmt::format("{}:{}: non-finite value; every axis component must be a "
                                     "finite number", source, number));
      }
    }
    rows.push_back(std::move(values));
    lines.push_back(number);
  }
  if (rows.empty()) throw InputError(source + ": no axes in the geometry file; " + kForms);
  return from_rows(source, rows, lines);
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

}  // namespace

Axis axis_from_azimuth_elevation(double az_deg, double el_deg) {
  const double az = az_deg * kDegToRad;
  const double el = el_deg * kDegToRad;
  return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
}

Geometry cone_geometry(std::size_t n, double half_angle_deg) {
  if (n < 3) {
    throw InputError(fmt::format("cone:{}: a unit needs at least 3 sensors (4 to detect a fault, "
                                 "5 to isolate one)", n));
  }
  if (!(half_angle_deg > 0.0 && half_angle_deg < 180.0) || half_angle_deg == 90.0) {
    throw InputError(fmt::format("cone half-angle {} deg: the axes must leave the cone's axis "
                                 "and its base plane (0 < DEG < 180, not 90: coplanar axes do "
                                 "not span 3-D)", half_angle_deg));
  }
  const double a = half_angle_deg * kDegToRad;
  std::vector<Axis> axes;
  for (std::size_t i = 0; i < n; ++i) {
    const double az = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
    Axis h{std::sin(a) * std::cos(az), std::sin(a) * std::sin(az), std::cos(a)};
    for (auto& c : h) c = std::abs(c) < 1e-15 ? 0.0 : c;  // cos 90 deg is 6e-17, not 0
    axes.push_back(h);
  }
  return geometry_from_axes(fmt::format("cone:{}:{:g}", n, half_angle_deg), std::move(axes));
}

Geometry make_geometry(std::string_view spec_in) {
  const std::string spec = trim(spec_in);
  const std::string key = lower(spec);
  if (key.empty()) throw InputError(std::string("empty --geometry; ") + kForms);
  if (key == "tetra") {
    Geometry g = cone_geometry(4, kTetraHalfAngleDeg);
    g.name = "tetra";
    return g;
  }
  if (key == "3+1") {
    const double s = 1.0 / std::sqrt(3.0);
    return geometry_from_axes("3+1", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {s, s, s}});
  }
  if (key == "dodeca") {
    const double phi = std::numbers::phi;
    Geometry g = geometry_from_axes(
        "dodeca", {{0, 1, phi}, {0, -1, phi}, {1, phi, 0}, {-1, phi, 0}, {phi, 0, 1}, {-phi, 0, 1}});
    g.notes.clear();  // the built-in vectors are normalised by design, not a user's slip
    return g;
  }
  if (key.rfind("triads:", 0) == 0) {
    // K co-aligned orthogonal triads (a flight controller's IMUs): rows x, y, z of triad 1, then
    // of triad 2, ..., the order of a PX4 log's instances gyro0_x .. gyroK_z.
    const std::string k_text = key.substr(7);
    std::size_t k = 0;
    const auto [p, ec] = std::from_chars(k_text.data(), k_text.data() + k_text.size(), k);
    if (ec != std::errc() || p != k_text.data() + k_text.size() || k == 0 || k > 64) {
      throw InputError("--geometry '" + spec + "': write triads:K with K the number of co-aligned triads (1 to 64)");
    }
    std::vector<Axis> axes;
    for (std::size_t t = 0; t < k; ++t) {
      axes.push_back({1, 0, 0});
      axes.push_back({0, 1, 0});
      axes.push_back({0, 0, 1});
    }
    return geometry_from_axes("triads:" + std::to_string(k), std::move(axes));
  }
  if (key.rfind("cone:", 0) == 0) {
    const auto second = key.find(':', 5);
    if (second == std::string::npos) {
      throw InputError("--geometry '" + spec + "': write cone:N:DEG (N sensors, half-angle in deg)");
    }
    const std::string n_text = key.substr(5, second - 5);
    std::size_t n = 0;
    const auto [p, ec] = std::from_chars(n_text.data(), n_text.data() + n_text.size(), n);
    if (ec != std::errc() || p != n_text.data() + n_text.size()) {
      throw InputError("--geometry '" + spec + "': '" + n_text + "' is not a sensor count; write cone:N:DEG");
    }
    const double deg = number_or_throw(key.substr(second + 1), "--geometry '" + spec + "'");
    return cone_geometry(n, deg);
  }
  const std::filesystem::path path(spec);
  if (!std::filesystem::exists(path)) {
    throw InputError("--geometry '" + spec + "': no such built-in geometry or file; " + kForms);
  }
  return read_geometry_file(path);
}

Geometry read_geometry_file(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw InputError(path.string() + ": not a readable file; " + kForms);
  }
  const std::string ext = lower(path.extension().string());
  if (ext == ".yaml" || ext == ".yml") return read_yaml(path);
  return read_text(path);
}

Geometry geometry_from_axes(std::string name, std::vector<Axis> axes) {
  Geometry g;
  g.name = std::move(name);
  if (axes.size() < 3) {
    throw InputError(fmt::format("{}: {} sensing axes; a unit needs at least 3 (4 to detect a "
                                 "fault, 5 to isolate one)", g.name, axes.size()));
  }
  for (std::size_t i = 0; i < axes.size(); ++i) {
    auto& a = axes[i];
    const double norm = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (!std::isfinite(norm) || norm < 1e-12) {
      throw InputError(fmt::format("{}: axis {} ({}, {}, {}) has no direction; every sensing axis "
                                   "needs a non-zero finite vector", g.name, i + 1, a[0], a[1], a[2]));
    }
    if (std::abs(norm - 1.0) > kUnitTolerance) {
      g.notes.push_back(fmt::format("axis {} had length {:.6g}: normalised", i + 1, norm));
    }
    for (auto& c : a) c /= norm;
  }
  Eigen::Matrix3d hth = Eigen::Matrix3d::Zero();
  for (const auto& a : axes) {
    const Eigen::Vector3d h(a[0], a[1], a[2]);
    hth += h * h.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(hth);
  const auto ev = eig.eigenvalues();
  if (!(ev(0) >= kSpanTolerance * ev(2))) {
    throw InputError(fmt::format("{}: the {} sensing axes do not span 3-D (they are coplanar or "
                                 "collinear; H^T H eigenvalues {:.3g}, {:.3g}, {:.3g}): one body "
                                 "rate component would be unobservable; tilt an axis out of the "
                                 "common plane", g.name, axes.size(), ev(0), ev(1), ev(2)));
  }
  g.axes = std::move(axes);
  return g;
}

Matrix measurement_matrix(const Geometry& geometry) {
  Matrix h(geometry.size(), 3);
  for (std::size_t i = 0; i < geometry.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) h(i, c) = geometry.axes[i][c];
  }
  return h;
}

}  // namespace imunoise::redundant
