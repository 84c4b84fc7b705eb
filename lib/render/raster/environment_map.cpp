#include "render/raster/environment_map.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "render/latlong.h"

namespace sdg {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Internally every image is an ImageRgbaF (4 floats a texel, alpha carried
// along and dropped at the end) so that one SSE operation filters a texel.
using Texel = Eigen::Array4f;

Eigen::Map<const Texel> texelAt(const ImageRgbaF& image, int x, int y) {
  return Eigen::Map<const Texel>(image.pixels.data() + 4 * (size_t(y) * image.width + size_t(x)));
}

Eigen::Map<Texel> texelAt(ImageRgbaF& image, int x, int y) {
  return Eigen::Map<Texel>(image.pixels.data() + 4 * (size_t(y) * image.width + size_t(x)));
}

ImageRgbaF blankImage(int width, int height) {
  return ImageRgbaF{uint32_t(width), uint32_t(height), std::vector<float>(size_t(width) * size_t(height) * 4, 0.0f)};
}

LatLong toLatLong(const ImageRgbaF& image) {
  LatLong out{int(image.width), int(image.height), std::vector<float>(size_t(image.width) * image.height * 3)};
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
    for (size_t c = 0; c < 3; ++c) out.rgb[3 * i + c] = image.pixels[4 * i + c];
  return out;
}

int defaultThreads() { return int(std::clamp(std::thread::hardware_concurrency(), 1u, 8u)); }

// Runs fn(item) for items 0 .. count - 1 on up to `threads` threads. Items
// are handed out one at a time, and each is computed the same whichever
// thread takes it, so results do not depend on the thread count.
template <class Fn>
void parallelFor(int count, int threads, const Fn& fn) {
  std::atomic<int> next{0};
  auto work = [&] {
    for (int i; (i = next.fetch_add(1, std::memory_order_relaxed)) < count;) fn(i);
  };
  std::vector<std::thread> helpers;
  for (int t = 1; t < std::min(threads, count); ++t) helpers.emplace_back(work);
  work();
  for (std::thread& helper : helpers) helper.join();
}

// cos(a) - cos(b), written as a product so that thin bands near the poles
// keep their precision (the difference of two cosines close to 1 does not).
double cosDifference(double a, double b) { return 2.0 * std::sin(0.5 * (a + b)) * std::sin(0.5 * (b - a)); }

// The longitude at column coordinate `x` of a map `width` wide (latlong.h).
double longitudeAt(double x, int width) { return (0.5 - x / width) * 2.0 * kPi; }

// ---------------------------------------------------------------------------
// Separable sums over lat-long texels.

// The source texels one target texel covers along an axis, each with a
// measure of the part of it covered.
struct Tap {
  int index;
  float weight;
};
struct Footprint {
  int begin, end;  // into AxisTaps::taps
  float norm;      // 1 / the sum of the weights
};
struct AxisTaps {
  std::vector<Tap> taps;
  std::vector<Footprint> footprints;
};

// `measure(a, b)` is the measure of the source interval [a, b], in source
// texel units.
template <class Measure>
AxisTaps axisTaps(int source, int target, const Measure& measure) {
  AxisTaps axis;
  for (int i = 0; i < target; ++i) {
    const double begin = double(i) * source / target, end = double(i + 1) * source / target;
    Footprint footprint{int(axis.taps.size()), 0, 0.0f};
    double sum = 0;
    for (int j = int(begin); j < source && j < end; ++j) {
      const double a = std::max(begin, double(j)), b = std::min(end, j + 1.0);
      if (b <= a) continue;
      const double w = measure(a, b);
      axis.taps.push_back({j, float(w)});
      sum += w;
    }
    footprint.end = int(axis.taps.size());
    footprint.norm = float(1.0 / sum);
    axis.footprints.push_back(footprint);
  }
  return axis;
}

// Each target texel is the sum over the source texels it overlaps of their
// value times across(overlap in x) times down(overlap in y), or, if
// `average`, that sum over the sum of the weights.
ImageRgbaF separableSum(const ImageRgbaF& source, const AxisTaps& across, const AxisTaps& down, bool average,
                        int threads) {
  const int width = int(across.footprints.size()), height = int(down.footprints.size());
  ImageRgbaF target = blankImage(width, height);
  parallelFor(height, threads, [&](int y) {
    const Footprint& rows = down.footprints[size_t(y)];
    for (int r = rows.begin; r < rows.end; ++r) {
      const Tap row = down.taps[size_t(r)];
      for (int x = 0; x < width; ++x) {
        const Footprint& columns = across.footprints[size_t(x)];
        Texel sum = Texel::Zero();
        for (int c = columns.begin; c < columns.end; ++c) {
          const Tap column = across.taps[size_t(c)];
          sum += column.weight * texelAt(source, column.index, row.index);
        }
        texelAt(target, x, y) += row.weight * sum;
      }
    }
    if (average)
      for (int x = 0; x < width; ++x) texelAt(target, x, y) *= rows.norm * across.footprints[size_t(x)].norm;
  });
  return target;
}

// Area-weighted resampling: each target texel is the average of the source
// over its footprint, each source texel weighted by the solid angle the two
// share, its longitude span times the difference of cos(polar angle) across
// the shared band. So the integral of radiance over the sphere is kept.
ImageRgbaF resample(const ImageRgbaF& source, int width, int height, int threads) {
  const int sh = int(source.height);
  return separableSum(source, axisTaps(int(source.width), width, [](double a, double b) { return b - a; }),
                      axisTaps(sh, height, [sh](double a, double b) { return cosDifference(a * kPi / sh, b * kPi / sh); }),
                      true, threads);
}

// The chain GL would hold for `base`: each level half the previous (rounded
// down, at least 1), down to 1 x 1.
std::vector<ImageRgbaF> mipChain(ImageRgbaF base, int threads) {
  std::vector<ImageRgbaF> chain;
  chain.push_back(std::move(base));
  while (chain.back().width > 1 || chain.back().height > 1) {
    const ImageRgbaF& last = chain.back();
    chain.push_back(resample(last, std::max(1, int(last.width) / 2), std::max(1, int(last.height) / 2), threads));
  }
  return chain;
}

// ---------------------------------------------------------------------------
// Irradiance.
//
// E(n) = integral of L(d) max(n.d, 0) over the sphere. Over a texel wholly
// above n's horizon the clamp does nothing and n.d is linear in d, so the
// texel gives exactly n . M, M = integral of L(d) d dOmega over the texel,
// its first moment, whatever the radiance inside it. The moments are
// integrated from the finest copy of the map kept (specular level 0, its
// texels taken as uniform), the directions' integrals in closed form.
// Summed along each row (prefix sums), a run of wholly lit texels costs one
// difference; only the texels the horizon crosses are clamped one by one,
// as max(n . M, 0), which is exact unless light falls on both sides of it.

// The moments of a map twice the irradiance map's size: for each channel
// (RGBA), the x, y and z components of M, and per row their prefix sums.
struct Moments {
  int width = 0, height = 0;
  ImageRgbaF x, y, z;
  std::vector<Eigen::Matrix<double, 4, 3>> prefix;  // (width + 1) per row; columns x, y, z
};

// Over a texel spanning polar angles [t0, t1] from +Y and longitudes
// [p0, p1], with d = (sin t sin p, cos t, sin t cos p) and dOmega = sin t dt
// dp, the moment of a constant radiance L is L times
//   (A (cos p0 - cos p1), B (p1 - p0), A (sin p1 - sin p0)),
// A = integral of sin^2 t dt, B = integral of sin t cos t dt: a product of
// one factor per axis, so the moments are separable sums of the map.
Moments momentsOf(const ImageRgbaF& map, int width, int height, int threads) {
  const int mw = int(map.width), mh = int(map.height);
  const auto polar = [mh](double a) { return a * kPi / mh; };
  // A and B of the band [a, b], as products where differences would cancel.
  const auto sinSquared = [&](double a, double b) {
    return (polar(b) - polar(a)) / 2.0 - std::sin(polar(b) - polar(a)) * std::cos(polar(b) + polar(a)) / 2.0;
  };
  const auto sinCos = [&](double a, double b) { return std::sin(polar(b) - polar(a)) * std::sin(polar(b) + polar(a)) / 2.0; };
  // Column coordinates grow as longitude falls: [a, b] spans longitudes
  // [longitudeAt(b), longitudeAt(a)].
  const auto cosines = [mw](double a, double b) { return cosDifference(longitudeAt(b, mw), longitudeAt(a, mw)); };
  const auto span = [mw](double a, double b) { return longitudeAt(a, mw) - longitudeAt(b, mw); };
  const auto sines = [mw](double a, double b) { return std::sin(longitudeAt(a, mw)) - std::sin(longitudeAt(b, mw)); };
  const AxisTaps a = axisTaps(mh, height, sinSquared), b = axisTaps(mh, height, sinCos);
  Moments m{width, height, separableSum(map, axisTaps(mw, width, cosines), a, false, threads),
            separableSum(map, axisTaps(mw, width, span), b, false, threads),
            separableSum(map, axisTaps(mw, width, sines), a, false, threads), {}};
  m.prefix.assign(size_t(width + 1) * size_t(height), Eigen::Matrix<double, 4, 3>::Zero());
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      Eigen::Matrix<double, 4, 3> moment;
      moment << texelAt(m.x, col, row).cast<double>(), texelAt(m.y, col, row).cast<double>(),
          texelAt(m.z, col, row).cast<double>();
      const size_t at = size_t(row) * size_t(width + 1) + size_t(col);
      m.prefix[at + 1] = m.prefix[at] + moment;
    }
  return m;
}

// The half-width, in longitude, of the arc of the circle at polar angle
// `polar` that lies above the horizon of a normal with y component `ny` and
// horizontal length `rho`: there rho sin(polar) cos(dlongitude) > -ny cos(polar).
double litHalfWidth(double ny, double rho, double polar) {
  const double s = rho * std::sin(polar), t = -ny * std::cos(polar);
  if (s <= 1e-12) return t < 0.0 ? kPi : 0.0;
  return std::acos(std::clamp(t / s, -1.0, 1.0));
}

// The sum of the moments of columns [first, first + count) of `row`, on the
// circle (count <= width).
Eigen::Matrix<double, 4, 3> runMoment(const Moments& m, int row, int first, int count) {
  const int w = m.width;
  const int start = ((first % w) + w) % w;
  const auto at = [&](int col) { return m.prefix[size_t(row) * size_t(w + 1) + size_t(col)]; };
  if (start + count <= w) return at(start + count) - at(start);
  return at(w) - at(start) + at(start + count - w);
}

Texel clampedTexel(const Moments& m, int row, int col, const Vec3f& n) {
  const int c = ((col % m.width) + m.width) % m.width;
  return (n.x() * texelAt(m.x, c, row) + n.y() * texelAt(m.y, c, row) + n.z() * texelAt(m.z, c, row)).max(0.0f);
}

// The irradiance from one source row whose texels are wholly lit within
// `full` and partly lit within `partial` source columns of `centre`, the
// normal's column coordinate.
Eigen::Vector4d rowIrradiance(const Moments& m, int row, const Eigen::Vector3d& n, double centre, double full,
                              double partial) {
  int first = int(std::ceil(centre - full)), end = int(std::floor(centre + full));
  const int partialFirst = int(std::floor(centre - partial));
  const int partialEnd = std::min(int(std::ceil(centre + partial)), partialFirst + m.width);
  if (end - first >= m.width) return runMoment(m, row, 0, m.width) * n;
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  if (end > first) sum += runMoment(m, row, first, end - first) * n;
  else first = end = partialEnd;
  const Vec3f nf = n.cast<float>();
  Texel edge = Texel::Zero();
  for (int col = partialFirst; col < first; ++col) edge += clampedTexel(m, row, col, nf);
  for (int col = end; col < partialEnd; ++col) edge += clampedTexel(m, row, col, nf);
  return sum + edge.cast<double>().matrix();
}

// E(n) / pi at the centres of a width x width / 2 map.
ImageRgbaF convolveIrradiance(const Moments& m, int width, int threads) {
  const int height = width / 2;
  ImageRgbaF target = blankImage(width, height);
  parallelFor(height, threads, [&](int y) {
    const double polar = (y + 0.5) * kPi / height;
    // A row's normals share their polar angle, so the lit arcs of each
    // source row edge, in source columns.
    std::vector<double> halfWidths(size_t(m.height) + 1);
    for (int e = 0; e <= m.height; ++e)
      halfWidths[size_t(e)] = litHalfWidth(std::cos(polar), std::sin(polar), e * kPi / m.height) * m.width / (2.0 * kPi);
    for (int x = 0; x < width; ++x) {
      const double longitude = longitudeAt(x + 0.5, width);
      const Eigen::Vector3d n(std::sin(polar) * std::sin(longitude), std::cos(polar), std::sin(polar) * std::cos(longitude));
      const double centre = (x + 0.5) * m.width / width;
      Eigen::Vector4d sum = Eigen::Vector4d::Zero();
      for (int row = 0; row < m.height; ++row) {
        const double a = halfWidths[size_t(row)], b = halfWidths[size_t(row) + 1];
        sum += rowIrradiance(m, row, n, centre, std::min(a, b), std::max(a, b));
      }
      texelAt(target, x, y) = (sum / kPi).cast<float>().array();
    }
  });
  return target;
}

// ---------------------------------------------------------------------------
// GGX importance sampling, shared by the specular chain and the table.

// The i-th of n Hammersley points, (i / n, the base-2 radical inverse of
// i), as the cosine and sine of the azimuth 2 pi x and y itself: a fixed
// sequence, the same for every texel.
struct SamplePoint {
  float cosPhi, sinPhi, y;
};

std::vector<SamplePoint> hammersley(int n) {
  std::vector<SamplePoint> points;
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    const double phi = 2.0 * kPi * i / n;
    points.push_back({float(std::cos(phi)), float(std::sin(phi)), float(bits * 2.3283064365386963e-10)});
  }
  return points;
}

// A half vector drawn from the GGX distribution of `alpha` around +Z
// (Karis's ImportanceSampleGGX).
Vec3f ggxHalfVector(const SamplePoint& p, float alpha) {
  const float a2 = alpha * alpha;
  const float cosTheta = std::sqrt((1.0f - p.y) / (1.0f + (a2 - 1.0f) * p.y));
  const float sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
  return {sinTheta * p.cosPhi, sinTheta * p.sinPhi, cosTheta};
}

float ggxD(float nh, float alpha) {
  const float a2 = alpha * alpha, d = nh * nh * (a2 - 1.0f) + 1.0f;
  return a2 / (kLatLongPi * d * d);
}

// ---------------------------------------------------------------------------
// Specular: GGX pre-convolution by filtered importance sampling.

// A light direction of the pre-convolution in the frame of N = V = R (+Z),
// its weight N.L, and log2 of the solid angle it stands for,
// 1 / (count * pdf(L)) (Colbert and Krivanek).
struct GgxSample {
  Vec3f direction;
  float weight;
  float log2SolidAngle;
};

std::vector<GgxSample> ggxSamples(float roughness, int count) {
  const float alpha = roughness * roughness;
  std::vector<GgxSample> samples;
  for (const SamplePoint& p : hammersley(count)) {
    const Vec3f h = ggxHalfVector(p, alpha);
    const Vec3f l = 2.0f * h.z() * h - Vec3f::UnitZ();  // reflect V = N about H
    if (l.z() <= 0.0f) continue;
    // pdf(L) = D(H) (N.H) / (4 V.H), and N.H = V.H when N = V.
    const float pdf = ggxD(h.z(), alpha) / 4.0f;
    samples.push_back({l, l.z(), -std::log2(float(count) * pdf)});
  }
  return samples;
}

// One bilinear read of a mip for a sample, the same for every texel of an
// output row but for the column: u = column * uScale + uOffset in the mip's
// texel units. The weights include the sample's N.L and trilinear share.
struct MipTap {
  const float* row0;  // the mip's two rows, 4 floats a texel
  const float* row1;
  int width;
  float weight0, weight1;
  float uScale, uOffset;
};

// The first texel of row `y` of a level `width` x `height`: its normal and
// the directions of growing longitude and polar angle. Every
// texel of the row is this one turned about +Y, frame and samples alike, so
// all read the same rows of the source, shifted in u.
struct RowFrame {
  Vec3f n, t, b;
};

RowFrame rowFrame(int width, int height, int y) {
  const float u = 0.5f / float(width), v = (float(y) + 0.5f) / float(height);
  const float polar = v * kLatLongPi, longitude = (0.5f - u) * 2.0f * kLatLongPi;
  return {directionFromLatLong(u, v), Vec3f(std::cos(longitude), 0.0f, -std::sin(longitude)),
          Vec3f(std::cos(polar) * std::sin(longitude), -std::sin(polar), std::cos(polar) * std::cos(longitude))};
}

// The mip a sample along latlong.h's v reads: the one whose texels have
// the sample's solid angle, log2 of the ratio halved, plus one (Colbert and
// Krivanek's bias against aliasing). A lat-long texel's solid angle shrinks
// with sin(polar angle).
float sampleLod(const GgxSample& s, float v, const ImageRgbaF& base, int lastMip) {
  const float sinPolar = std::max(std::sin(v * kLatLongPi), std::sin(0.5f * kLatLongPi / float(base.height)));
  const float texelSolidAngle = 2.0f * kLatLongPi * kLatLongPi / (float(base.width) * float(base.height)) * sinPolar;
  return std::clamp(0.5f * (s.log2SolidAngle - std::log2(texelSolidAngle)) + 1.0f, 0.0f, float(lastMip));
}

// A bilinear read of `mip` at `uv` for the first texel of a row of an
// output level `width` wide, weighted by `weight`, and for the others.
MipTap bilinearTap(const ImageRgbaF& mip, const Eigen::Vector2f& uv, int width, float weight) {
  const int mw = int(mip.width), mh = int(mip.height);
  const float vv = std::clamp(uv.y() * float(mh) - 0.5f, 0.0f, float(mh - 1));
  const int row0 = std::min(int(vv), mh - 1), row1 = std::min(row0 + 1, mh - 1);
  const float down = vv - float(row0);
  // Texel x of the row reads at u = uv.x + x / width.
  float offset = std::fmod(uv.x() * float(mw) - 0.5f, float(mw));
  if (offset < 0.0f) offset += float(mw);
  const float* pixels = mip.pixels.data();
  return {pixels + 4 * size_t(row0) * size_t(mw), pixels + 4 * size_t(row1) * size_t(mw), mw,
          weight * (1.0f - down), weight * down, float(mw) / float(width), offset};
}

// The reads of sample `s` for a row: the two mips around its lod, weighted
// by N.L and their trilinear shares.
void addSampleTaps(const GgxSample& s, const RowFrame& frame, int width, const std::vector<ImageRgbaF>& chain,
                   std::vector<MipTap>& taps) {
  const Vec3f l = s.direction.x() * frame.t + s.direction.y() * frame.b + s.direction.z() * frame.n;
  const Eigen::Vector2f uv = latLongFromDirection(l);
  const int last = int(chain.size()) - 1;
  const float lod = sampleLod(s, uv.y(), chain[0], last);
  const int mip = std::min(int(lod), last);
  const float upper = mip == last ? 0.0f : lod - float(mip);
  taps.push_back(bilinearTap(chain[size_t(mip)], uv, width, s.weight * (1.0f - upper)));
  if (upper > 0.0f) taps.push_back(bilinearTap(chain[size_t(mip) + 1], uv, width, s.weight * upper));
}

// Adds one tap's bilinear reads for every texel of an output row to `row`.
void addTapReads(const MipTap& tap, std::vector<Texel>& row) {
  using Read = Eigen::Map<const Texel>;
  for (size_t x = 0; x < row.size(); ++x) {
    const float u = float(x) * tap.uScale + tap.uOffset;
    int c0 = int(u);
    const float right = u - float(c0);
    while (c0 >= tap.width) c0 -= tap.width;
    const int c1 = c0 + 1 == tap.width ? 0 : c0 + 1;
    const Texel left = tap.weight0 * Read(tap.row0 + 4 * c0) + tap.weight1 * Read(tap.row1 + 4 * c0);
    const Texel next = tap.weight0 * Read(tap.row0 + 4 * c1) + tap.weight1 * Read(tap.row1 + 4 * c1);
    row[x] += left + right * (next - left);
  }
}

// A level of the specular chain past 0, with its samples.
struct SpecularLevel {
  std::vector<GgxSample> samples;
  float totalWeight = 0;
  ImageRgbaF image;
};

// Levels 1 .. levels - 1 of the specular chain, rows of all levels handed
// out together (the largest level first). Level k takes `samples` << (k - 1)
// samples: each level has a quarter of the texels of the one before, and
// more samples keep the reads of wide lobes on finer mips.
std::vector<ImageRgbaF> convolveSpecular(const std::vector<ImageRgbaF>& chain, int levels, int samples, int threads) {
  std::vector<SpecularLevel> out;
  std::vector<std::pair<int, int>> rows;  // (index into out, row)
  for (int k = 1; k < levels; ++k) {
    SpecularLevel level{ggxSamples(float(k) / float(levels - 1), samples << (k - 1)), 0.0f,
                        blankImage(int(chain[size_t(k)].width), int(chain[size_t(k)].height))};
    for (const GgxSample& s : level.samples) level.totalWeight += s.weight;
    for (int y = 0; y < int(level.image.height); ++y) rows.emplace_back(k - 1, y);
    out.push_back(std::move(level));
  }
  parallelFor(int(rows.size()), threads, [&](int item) {
    const auto [index, y] = rows[size_t(item)];
    SpecularLevel& level = out[size_t(index)];
    const int width = int(level.image.width);
    const RowFrame frame = rowFrame(width, int(level.image.height), y);
    std::vector<MipTap> taps;
    taps.reserve(2 * level.samples.size());
    for (const GgxSample& s : level.samples) addSampleTaps(s, frame, width, chain, taps);
    std::vector<Texel> row(size_t(width), Texel::Zero());
    for (const MipTap& tap : taps) addTapReads(tap, row);
    for (int x = 0; x < width; ++x) texelAt(level.image, x, y) = row[size_t(x)] / level.totalWeight;
  });
  std::vector<ImageRgbaF> images;
  for (SpecularLevel& level : out) images.push_back(std::move(level.image));
  return images;
}

// ---------------------------------------------------------------------------
// The split-sum table.

// Schlick's approximation of Smith's G for GGX with k = alpha / 2, as in
// shaders.h's brdf().
float smithSchlick(float nl, float nv, float alpha) {
  const float k = alpha / 2.0f;
  return (nl / (nl * (1.0f - k) + k)) * (nv / (nv * (1.0f - k) + k));
}

// Karis's IntegrateBRDF: the specular BRDF times N.L integrated over L by
// importance sampling GGX, split into the parts that multiply F0 and 1.
Eigen::Vector2f integrateSplitSum(float nv, float roughness, const std::vector<SamplePoint>& points) {
  const float alpha = std::max(roughness * roughness, 1e-3f);
  const Vec3f v(std::sqrt(1.0f - nv * nv), 0.0f, nv);
  Eigen::Vector2f sum = Eigen::Vector2f::Zero();
  for (const SamplePoint& p : points) {
    const Vec3f h = ggxHalfVector(p, alpha);
    const float vh = v.dot(h);
    const Vec3f l = 2.0f * vh * h - v;
    if (l.z() <= 0.0f || vh <= 0.0f) continue;
    // BRDF * N.L / pdf(L), pdf(L) = D (N.H) / (4 V.H): D cancels.
    const float g = smithSchlick(l.z(), nv, alpha) * vh / (h.z() * nv);
    const float m = 1.0f - vh, fresnel = m * m * m * m * m;
    sum += Eigen::Vector2f((1.0f - fresnel) * g, fresnel * g);
  }
  return sum / float(points.size());
}

// ---------------------------------------------------------------------------

void checkInputs(const ImageRgbaF& map, const EnvironmentSettings& s) {
  if (map.width == 0 || map.height == 0 || map.pixels.size() != size_t(map.width) * map.height * 4)
    throw std::invalid_argument("prefilterEnvironment: the map is empty or its pixels do not match its size");
  if (s.irradianceWidth < 2 || s.irradianceWidth % 2 || s.specularBaseWidth < 1 || s.specularLevels < 1 ||
      s.specularSamples < 1 || s.specularSamples > 4096 || s.threads < 0)
    throw std::invalid_argument("prefilterEnvironment: settings out of range");
}

}  // namespace

PrefilteredEnvironment prefilterEnvironment(const ImageRgbaF& map, const EnvironmentSettings& settings) {
  checkInputs(map, settings);
  const int threads = settings.threads > 0 ? settings.threads : defaultThreads();
  const int baseWidth = std::min(int(map.width), settings.specularBaseWidth);
  const int baseHeight = std::max(1, int(int64_t(map.height) * baseWidth / int64_t(map.width)));
  const std::vector<ImageRgbaF> chain = mipChain(resample(map, baseWidth, baseHeight, threads), threads);
  const int levels = std::min(settings.specularLevels, int(chain.size()));

  PrefilteredEnvironment result;
  const int width = settings.irradianceWidth;
  result.irradiance = toLatLong(convolveIrradiance(momentsOf(chain[0], 2 * width, width, threads), width, threads));
  result.specular.push_back(toLatLong(chain[0]));
  for (const ImageRgbaF& level : convolveSpecular(chain, levels, settings.specularSamples, threads))
    result.specular.push_back(toLatLong(level));
  return result;
}

SplitSumLut integrateSplitSumLut(int size) {
  if (size < 1) throw std::invalid_argument("integrateSplitSumLut: size must be at least 1");
  const std::vector<SamplePoint> points = hammersley(1024);  // Karis's count
  SplitSumLut lut{size, std::vector<float>(size_t(size) * size_t(size) * 2)};
  parallelFor(size, defaultThreads(), [&](int j) {
    for (int i = 0; i < size; ++i) {
      const Eigen::Vector2f v = integrateSplitSum((float(i) + 0.5f) / float(size), (float(j) + 0.5f) / float(size), points);
      lut.scaleBias[2 * (size_t(j) * size_t(size) + size_t(i))] = v.x();
      lut.scaleBias[2 * (size_t(j) * size_t(size) + size_t(i)) + 1] = v.y();
    }
  });
  return lut;
}

double latLongTexelSolidAngle(int width, int height, int row) {
  return 2.0 * kPi / width * cosDifference(row * kPi / height, (row + 1) * kPi / height);
}

Vec3f sampleBilinear(const LatLong& image, const Vec3f& dir) {
  const Eigen::Vector2f uv = latLongFromDirection(dir);
  const float x = uv.x() * float(image.width) - 0.5f, y = uv.y() * float(image.height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float right = x - fx, down = y - fy;
  const int c0 = ((int(fx) % image.width) + image.width) % image.width, c1 = (c0 + 1) % image.width;
  const int r0 = std::clamp(int(fy), 0, image.height - 1), r1 = std::clamp(int(fy) + 1, 0, image.height - 1);
  const auto at = [&](int c, int r) {
    return Eigen::Map<const Vec3f>(image.rgb.data() + 3 * (size_t(r) * size_t(image.width) + size_t(c)));
  };
  return (1.0f - down) * ((1.0f - right) * at(c0, r0) + right * at(c1, r0)) +
         down * ((1.0f - right) * at(c0, r1) + right * at(c1, r1));
}

}  // namespace sdg
