#pragma once
// Shared by the path tracer's tests: inline YAML scenes turned into render
// lists, a finely tessellated sphere mesh, and quadratures of the BSDF for
// the values the analytic scenes expect.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "render/pathtrace/bsdf.h"
#include "render/pathtrace/path_tracer.h"
#include "render/render_list.h"
#include "scene_io/scene_loader.h"
#include "scratch_name.h"

namespace sdg::pttest {

inline constexpr double kPi = 3.14159265358979323846;

inline std::filesystem::path scratchFolder(const std::string& name) {
  std::filesystem::path dir = std::filesystem::path(SDG_BINARY_DIR) / "pathtrace" / name;
  std::filesystem::create_directories(dir);
  return dir;
}

inline RenderList renderListOf(const std::string& yaml) {
  Scene scene = buildScene(sceneDocumentFromText(yaml, "t.yaml"), builtinRegistry().catalog());
  return buildRenderList(scene.stage);
}

inline const AssetResolver& testAssets() {
  static const AssetResolver assets({SDG_SOURCE_DIR "/scenes", SDG_SOURCE_DIR "/tests/data"});
  return assets;
}

inline PathTracedFrame trace(const RenderList& list, int width, int height, PathTraceSettings settings,
                             uint64_t seed = 1, size_t camera = 0) {
  PathTracer tracer(testAssets(), settings);
  PathTracedFrame frame;
  tracer.render(list, camera, width, height, seed, frame);
  return frame;
}

// The zone of the unit sphere between polar angles theta0 and theta1 (from
// +Z) as an OBJ file `name` in the scratch folder: a latitude-longitude
// grid of `rows` x 256, with the exact normals at the vertices (no
// degenerate triangles at a pole).
inline std::string sphereZoneObj(const std::string& name, double theta0, double theta1, int rows) {
  const std::filesystem::path file = scratchFolder("meshes") / name;
  if (std::filesystem::exists(file)) return file.string();
  const int columns = 256;
  // Written under a name of this process's own, then renamed: another test
  // process may be making the same file at the same time.
  const std::string scratch = file.string() + test::uniqueSuffix() + ".tmp";
  std::ofstream out(scratch);
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= columns; ++i) {
      const double theta = theta0 + (theta1 - theta0) * j / rows, phi = 2 * kPi * i / columns;
      const double x = std::sin(theta) * std::cos(phi), y = std::sin(theta) * std::sin(phi), z = std::cos(theta);
      out << "v " << x << ' ' << y << ' ' << z << "\nvn " << x << ' ' << y << ' ' << z << '\n';
    }
  auto index = [&](int i, int j) { return j * (columns + 1) + i + 1; };
  const bool northPole = theta0 == 0.0, southPole = theta1 == kPi;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      if (!(northPole && j == 0)) out << "f " << a << "//" << a << ' ' << d << "//" << d << ' ' << b << "//" << b << '\n';
      if (!(southPole && j == rows - 1))
        out << "f " << b << "//" << b << ' ' << d << "//" << d << ' ' << c << "//" << c << '\n';
    }
  out.close();
  std::filesystem::rename(scratch, file);
  return file.string();
}

// A unit sphere as an OBJ file: a latitude-longitude grid fine enough
// (256 x 128) that its facets stay within 0.03 % of the sphere, with the
// exact normals at the vertices. The procedural Sphere (48 x 24) is 0.2 %
// off, which the 1 % tests below would feel through the shading normals.
inline std::string fineSphereObj() { return sphereZoneObj("fine_sphere.obj", 0.0, kPi, 128); }

// The integral over the azimuth of the BSDF's f cos θi for view cosine
// muO and light cosine muI (both against the normal), by the midpoint rule
// (spectrally accurate for a smooth periodic integrand).
inline double azimuthIntegral(const PbrBsdf& bsdf, double muO, double muI, int steps = 256) {
  const Vec3f wo(float(std::sqrt(std::max(0.0, 1 - muO * muO))), 0.0f, float(muO));
  const double sinI = std::sqrt(std::max(0.0, 1 - muI * muI));
  double sum = 0;
  for (int k = 0; k < steps; ++k) {
    const double phi = 2 * kPi * (k + 0.5) / steps;
    const Vec3f wi(float(sinI * std::cos(phi)), float(sinI * std::sin(phi)), float(muI));
    sum += bsdf.eval(wo, wi).x();
  }
  return sum * 2 * kPi / steps;
}

// Gauss-Legendre nodes and weights on [a, b] (Newton's method on P_n).
inline void gaussLegendre(int n, double a, double b, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(size_t(n), 0.0);
  weights.assign(size_t(n), 0.0);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), derivative = 1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    nodes[size_t(i)] = 0.5 * (b - a) * x + 0.5 * (b + a);
    weights[size_t(i)] = (b - a) / ((1 - x * x) * derivative * derivative);
  }
}

// The BSDF's directional albedo (red channel) seen from cosine muO: the
// integral of f cos θi over the hemisphere, by Gauss-Legendre in cos θi
// (split where the GGX lobe peaks, at the mirror direction) times the
// azimuth rule above.
inline double directionalAlbedo(const PbrBsdf& bsdf, double muO) {
  std::vector<double> x1, w1, x2, w2;
  gaussLegendre(64, 0.0, muO, x1, w1);
  gaussLegendre(64, muO, 1.0, x2, w2);
  double sum = 0;
  for (size_t k = 0; k < x1.size(); ++k) sum += w1[k] * azimuthIntegral(bsdf, muO, x1[k]);
  for (size_t k = 0; k < x2.size(); ++k) sum += w2[k] * azimuthIntegral(bsdf, muO, x2[k]);
  return sum;
}

}  // namespace sdg::pttest
