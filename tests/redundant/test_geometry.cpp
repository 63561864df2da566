// Geometry and fusion analysis against the closed forms of ../shared/references.md
// ("Redundant gyro geometry") and identities (V H = 0, V V^T = I) on arbitrary geometries.
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <unistd.h>
#include <random>

#include <gtest/gtest.h>

#include "imunoise/error.hpp"
#include "imunoise/redundant/analysis.hpp"
#include "imunoise/redundant/geometry.hpp"

namespace {

using namespace imunoise;
using namespace imunoise::redundant;

// Independent 3x3 inverse by cofactors (not Eigen) for the closed-form checks.
std::array<std::array<double, 3>, 3> inverse3(const std::array<std::array<double, 3>, 3>& a) {
  std::array<std::array<double, 3>, 3> c{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      c[j][i] = a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1];  // transposed cofactor
    }
  }
  const double det = a[0][0] * c[0][0] + a[0][1] * c[1][0] + a[0][2] * c[2][0];
  for (auto& r : c) for (auto& v : r) v /= det;
  return c;
}

std::array<std::array<double, 3>, 3> hth(const std::vector<Axis>& axes) {
  std::array<std::array<double, 3>, 3> m{};
  for (const auto& h : axes) for (int i = 0; i < 3; ++i) for (int j = 0; j < 3; ++j) m[i][j] += h[i] * h[j];
  return m;
}

void expect_parity_identities(const Analysis& a) {
  const auto& v = a.parity;
  const auto& h = a.measurement;
  ASSERT_EQ(v.rows, a.geometry.size() - 3);
  for (std::size_t r = 0; r < v.rows; ++r) {
    for (std::size_t c = 0; c < 3; ++c) {
      double vh = 0;
      for (std::size_t i = 0; i < v.cols; ++i) vh += v(r, i) * h(i, c);
      EXPECT_NEAR(vh, 0.0, 1e-13) << "V H row " << r;
    }
    for (std::size_t r2 = 0; r2 < v.rows; ++r2) {
      double vv = 0;
      for (std::size_t i = 0; i < v.cols; ++i) vv += v(r, i) * v(r2, i);
      EXPECT_NEAR(vv, r == r2 ? 1.0 : 0.0, 1e-13) << "V V^T " << r << "," << r2;
    }
  }
  // G H = I: the fusion is unbiased for any body rate.
  for (std::size_t j = 0; j < 3; ++j) {
    for (std::size_t c = 0; c < 3; ++c) {
      double gh = 0;
      for (std::size_t i = 0; i < h.rows; ++i) gh += a.fusion(j, i) * h(i, c);
      EXPECT_NEAR(gh, j == c ? 1.0 : 0.0, 1e-13);
    }
  }
}

TEST(RedundantGeometry, TetraGainGdopAndParity) {
  const Analysis a = analyze_unit(make_geometry("tetra"));
  for (double g : a.axis_gain) EXPECT_NEAR(g, 0.8660, 5e-5);
  for (double g : a.axis_gain) EXPECT_NEAR(g, std::sqrt(3.0 / 4.0), 1e-13);
  EXPECT_NEAR(a.gdop, 1.500, 1e-12);
  ASSERT_EQ(a.parity.rows, 1u);
  const double expected[4] = {0.5, -0.5, 0.5, -0.5};
  const double sign = a.parity(0, 0) > 0 ? 1.0 : -1.0;
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(sign * a.parity(0, i), expected[i], 1e-13);
  EXPECT_TRUE(a.detectable);
  EXPECT_FALSE(a.isolable);  // 4 sensors: detectable, not isolable (references.md)
  expect_parity_identities(a);
  // Without any one sensor: the other three, GDOP from an independent inverse.
  for (std::size_t i = 0; i < 4; ++i) {
    std::vector<Axis> rest;
    for (std::size_t s = 0; s < 4; ++s) if (s != i) rest.push_back(a.geometry.axes[s]);
    const auto p = inverse3(hth(rest));
    ASSERT_TRUE(a.gdop_without[i].has_value());
    EXPECT_NEAR(*a.gdop_without[i], std::sqrt(p[0][0] + p[1][1] + p[2][2]), 1e-12);
    EXPECT_GT(*a.gdop_without[i], a.gdop);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR((*a.axis_gain_without[i])[static_cast<std::size_t>(j)], std::sqrt(p[j][j]), 1e-12);
  }
}

TEST(RedundantGeometry, ThreePlusOne) {
  const Analysis a = analyze_unit(make_geometry("3+1"));
  for (double g : a.axis_gain) EXPECT_NEAR(g, 0.9129, 5e-5);
  for (double g : a.axis_gain) EXPECT_NEAR(g, std::sqrt(5.0 / 6.0), 1e-13);
  EXPECT_NEAR(a.gdop, 1.581, 5e-4);
  EXPECT_NEAR(a.gdop, std::sqrt(2.5), 1e-13);
  expect_parity_identities(a);
  // Without the skewed sensor: the orthogonal triad, GDOP sqrt 3.
  EXPECT_NEAR(*a.gdop_without[3], std::sqrt(3.0), 1e-13);
}

TEST(RedundantGeometry, ConeClosedForm) {
  // H^T H = diag(n sin^2 a / 2, n sin^2 a / 2, n cos^2 a) for a cone of n >= 3.
  for (std::size_t n_sensors : {3u, 5u, 6u, 8u}) {
    const double n = static_cast<double>(n_sensors);
    for (double deg : {30.0, 54.7356103172, 70.0}) {
      const Geometry g = cone_geometry(n_sensors, deg);
      const double a = deg * M_PI / 180.0;
      const auto m = hth(g.axes);
      EXPECT_NEAR(m[0][0], n * std::sin(a) * std::sin(a) / 2, 1e-12);
      EXPECT_NEAR(m[1][1], n * std::sin(a) * std::sin(a) / 2, 1e-12);
      EXPECT_NEAR(m[2][2], n * std::cos(a) * std::cos(a), 1e-12);
      EXPECT_NEAR(m[0][1], 0.0, 1e-12);
      const Analysis an = analyze_unit(g);
      EXPECT_NEAR(an.axis_gain[0], std::sqrt(2.0 / (n * std::sin(a) * std::sin(a))), 1e-12);
      EXPECT_NEAR(an.axis_gain[2], std::sqrt(1.0 / (n * std::cos(a) * std::cos(a))), 1e-12);
      if (n_sensors > 3) expect_parity_identities(an);
    }
  }
  // Isotropic cones: gain sqrt(3/n).
  const Analysis six = analyze_unit(make_geometry("cone:6:54.7356103172"));
  for (double g : six.axis_gain) EXPECT_NEAR(g, std::sqrt(0.5), 1e-9);
  EXPECT_TRUE(six.isolable);
}

TEST(RedundantGeometry, DodecaIsIsotropicAndIsolable) {
  const Analysis a = analyze_unit(make_geometry("dodeca"));
  ASSERT_EQ(a.geometry.size(), 6u);
  const auto m = hth(a.geometry.axes);
  for (int i = 0; i < 3; ++i) for (int j = 0; j < 3; ++j) EXPECT_NEAR(m[i][j], i == j ? 2.0 : 0.0, 1e-13);
  for (double g : a.axis_gain) EXPECT_NEAR(g, std::sqrt(0.5), 1e-13);
  EXPECT_NEAR(a.gdop, std::sqrt(1.5), 1e-13);
  EXPECT_TRUE(a.isolable);
  EXPECT_TRUE(a.geometry.notes.empty());
  // Any two axes at the dodecahedron's face-normal angle: |cos| = 1/sqrt 5.
  for (std::size_t i = 0; i < 6; ++i) {
    for (std::size_t j = i + 1; j < 6; ++j) {
      const auto& u = a.geometry.axes[i];
      const auto& v = a.geometry.axes[j];
      EXPECT_NEAR(std::abs(u[0] * v[0] + u[1] * v[1] + u[2] * v[2]), 1.0 / std::sqrt(5.0), 1e-13);
    }
  }
  expect_parity_identities(a);
}

TEST(RedundantGeometry, ParityIdentitiesOnRandomGeometries) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 50; ++trial) {
    const std::size_t n = 4 + static_cast<std::size_t>(trial % 6);
    std::vector<Axis> axes(n);
    for (auto& a : axes) for (auto& c : a) c = normal(rng);
    const Analysis an = analyze_unit(geometry_from_axes("random", axes));
    expect_parity_identities(an);
    // GDOP from the independent inverse.
    const auto p = inverse3(hth(an.geometry.axes));
    EXPECT_NEAR(an.gdop, std::sqrt(p[0][0] + p[1][1] + p[2][2]), 1e-10);
  }
}

TEST(RedundantGeometry, FilesYamlAndCsv) {
  const auto dir = std::filesystem::temp_directory_path() / ("imunoise-geom-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto tetra = make_geometry("tetra");
  {
    std::ofstream out(dir / "tetra.csv");
    out.precision(17);
    out << "# the tetrahedral cone\nx,y,z\n";
    for (const auto& a : tetra.axes) out << a[0] << "," << a[1] << "," << a[2] << "\n";
  }
  const auto fromcsv = analyze_unit(make_geometry((dir / "tetra.csv").string()));
  EXPECT_NEAR(fromcsv.gdop, 1.5, 1e-12);
  {
    std::ofstream out(dir / "azel.yaml");
    out.precision(17);
    out << "azimuth_elevation_deg:\n";
    for (int i = 0; i < 4; ++i) out << "  - [" << 90 * i << ", " << 90.0 - kTetraHalfAngleDeg << "]\n";
  }
  const auto fromyaml = analyze_unit(make_geometry((dir / "azel.yaml").string()));
  EXPECT_NEAR(fromyaml.gdop, 1.5, 1e-12);
  for (std::size_t i = 0; i < 4; ++i) for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(fromyaml.geometry.axes[i][c], tetra.axes[i][c], 1e-12);
  {
    std::ofstream out(dir / "scaled.yaml");
    out << "axes:\n  - [2, 0, 0]\n  - [0, 1, 0]\n  - [0, 0, 1]\n  - [1, 1, 1]\n";
  }
  const auto scaled = make_geometry((dir / "scaled.yaml").string());
  EXPECT_EQ(scaled.notes.size(), 2u);  // axes 1 and 4 normalised, each with a note
  EXPECT_NEAR(analyze_unit(scaled).gdop, std::sqrt(2.5), 1e-12);
  std::filesystem::remove_all(dir);
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RedundantGeometry, BadInputIsRefusedClearly) {
  const auto dir = std::filesystem::temp_directory_path() / ("imunoise-geombad-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  };
  EXPECT_NE(message_of([] { make_geometry("cone:2:50"); }).find("at least 3"), std::string::npos);
  EXPECT_NE(message_of([] { make_geometry("cone:4:90"); }).find("coplanar"), std::string::npos);
  EXPECT_NE(message_of([] { make_geometry("cone:x:50"); }).find("sensor count"), std::string::npos);
  EXPECT_NE(message_of([] { make_geometry("octahedron"); }).find("tetra, cone:N:DEG"), std::string::npos);
  const auto coplanar = write("flat.csv", "1,0,0\n0,1,0\n0.7071,0.7071,0\n-1,1,0\n");
  const auto m1 = message_of([&] { make_geometry(coplanar); });
  EXPECT_NE(m1.find("do not span 3-D"), std::string::npos) << m1;
  EXPECT_NE(m1.find("flat.csv"), std::string::npos) << m1;
  const auto four = write("four.csv", "1,0,0,1\n0,1,0,0\n0,0,1,0\n1,1,1,0\n");
  const auto m2 = message_of([&] { make_geometry(four); });
  EXPECT_NE(m2.find("four.csv:1: 4 fields"), std::string::npos) << m2;
  const auto mixed = write("mixed.csv", "1,0,0\n0,1,0\n0,0,1\n45,30\n");
  EXPECT_NE(message_of([&] { make_geometry(mixed); }).find("mixed.csv:4"), std::string::npos);
  const auto zero = write("zero.csv", "1,0,0\n0,1,0\n0,0,1\n0,0,0\n");
  EXPECT_NE(message_of([&] { make_geometry(zero); }).find("axis 4"), std::string::npos);
  const auto two = write("two.csv", "1,0,0\n0,1,0\n");
  EXPECT_NE(message_of([&] { make_geometry(two); }).find("at least 3"), std::string::npos);
  const auto text = write("text.csv", "x,y,z\n1,0,0\n0,one,0\n");
  EXPECT_NE(message_of([&] { make_geometry(text); }).find("text.csv:3"), std::string::npos);
  const auto yaml = write("bad.yaml", "axes:\n  - [1, 0]\n  - [0, 1, 0]\n  - [0, 0, 1]\n");
  EXPECT_NE(message_of([&] { make_geometry(yaml); }).find("bad.yaml:2: 2 fields"), std::string::npos);
  const auto empty = write("empty.csv", "# nothing\n");
  EXPECT_NE(message_of([&] { make_geometry(empty); }).find("no axes"), std::string::npos);
  // Models: one per sensor.
  std::vector<SensorModel> three(3);
  EXPECT_NE(message_of([&] { analyze_unit(make_geometry("tetra"), three); }).find("3 noise models for the 4 sensors"),
            std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace

namespace {

TEST(RedundantGeometry, ExampleFilesParse) {
  const auto root = std::filesystem::path(IMUNOISE_TEST_DATA_DIR).parent_path().parent_path() / "examples" / "geometries";
  const Analysis pentad = analyze_unit(make_geometry((root / "pentad.yaml").string()));
  EXPECT_EQ(pentad.geometry.size(), 5u);
  EXPECT_TRUE(pentad.detectable);
  EXPECT_FALSE(pentad.isolable);  // mirror pairs: parallel parity columns
  EXPECT_NEAR(pentad.axis_gain[0], std::sqrt(0.75), 1e-5);  // printed elevations have 6 digits
  EXPECT_TRUE(analyze_unit(make_geometry("cone:5:54.7356")).isolable);
  const Analysis tp1 = analyze_unit(make_geometry((root / "three_plus_one.csv").string()));
  EXPECT_NEAR(tp1.gdop, std::sqrt(2.5), 1e-12);
  EXPECT_EQ(tp1.geometry.notes.size(), 1u);  // (1,1,1) normalised
}

}  // namespace
