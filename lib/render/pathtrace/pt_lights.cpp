#include "render/pathtrace/pt_lights.h"

#include <algorithm>
#include <cmath>

#include "render/latlong.h"
#include "render/pathtrace/bsdf.h"

namespace sdg {
namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInf = std::numeric_limits<float>::infinity();

float luminance(const Vec3f& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

// Shirley and Chiu's concentric map of the square onto the unit disk: it
// keeps the sampler's stratification.
Vec2f concentricDisk(const Vec2f& u) {
  const float a = 2.0f * u.x() - 1.0f, b = 2.0f * u.y() - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  float r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = 0.25f * kPi * (b / a);
  } else {
    r = b;
    phi = 0.5f * kPi - 0.25f * kPi * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

// A direction uniform in the cone around `axis` whose 1 - cos(half-angle)
// is `oneMinusCosMax` (pbrt-v4's SampleUniformCone, written with 1 - cos so
// that a cone of a fraction of a degree keeps its precision in float).
Vec3f sampleCone(const Vec3f& axis, float oneMinusCosMax, const Vec2f& u) {
  const float oneMinusCos = u.x() * oneMinusCosMax;
  const float cosTheta = 1.0f - oneMinusCos;
  const float sinTheta = std::sqrt(std::max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
  const float phi = 2.0f * kPi * u.y();
  const ShadingFrame frame = ShadingFrame::fromNormal(axis);
  return frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta}).normalized();
}

}  // namespace

PtDomeMap::PtDomeMap(ImageRgbaF map) : image(std::move(map)), sampler(image), mean(Vec3f::Zero()) {
  // The solid-angle average: row y spans (2 pi / w)(cos θtop - cos θbottom) per texel.
  double sum[3] = {0, 0, 0};
  for (uint32_t y = 0; y < image.height; ++y) {
    const double top = std::cos(M_PI * y / image.height), bottom = std::cos(M_PI * (y + 1) / image.height);
    const double weight = (top - bottom) / (2.0 * image.width);  // over 4 pi: 2 pi / w / (4 pi)
    for (uint32_t x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float v = image.pixels[(size_t(y) * image.width + x) * 4 + size_t(c)];
        if (std::isfinite(v) && v > 0.0f) sum[c] += v * weight;
      }
  }
  mean = Vec3f(float(sum[0]), float(sum[1]), float(sum[2]));
}

Vec3f PtDomeMap::radiance(const Vec3f& domeDirection) const {
  const Vec2i texel = latLongTexel(domeDirection, image.width, image.height);
  const float* p = &image.pixels[(size_t(texel.y()) * image.width + size_t(texel.x())) * 4];
  return {p[0], p[1], p[2]};
}


PtLights::PtLights() = default;
PtLights::~PtLights() = default;

void PtLights::build(const RenderList& list, const Eigen::AlignedBox3f& sceneBounds,
                     const std::function<const PtDomeMap*(const RenderLight&)>& domeMap) {
  lights_.clear();
  pickCdf_.clear();
  anyLobeMultiplier_ = false;
  const float sceneRadius = sceneBounds.isEmpty() ? 1.0f : std::max(0.5f * sceneBounds.diagonal().norm(), 1e-3f);
  std::vector<double> power;
  Light dome;
  dome.kind = LightKind::Dome;
  bool anyDome = false;
  for (const RenderLight& in : list.lights) {
    if (in.kind == LightKind::Dome) {
      // The first dome with a texture shows it; the others add their colour.
      // The one dome light takes the first dome's diffuse and specular
      // multipliers, the textured one's where there is one.
      if (!anyDome || (!dome.map && !in.texture.empty())) {
        dome.diffuse = in.diffuse;
        dome.specular = in.specular;
        anyLobeMultiplier_ = anyLobeMultiplier_ || in.diffuse != 1.0f || in.specular != 1.0f;
      }
      anyDome = true;
      if (!dome.map && !in.texture.empty()) {
        dome.map = domeMap(in);
        dome.mapScale = in.radiance;
        dome.domeFromWorld = in.worldRotation.transpose().cast<float>();
      } else {
        dome.ambient += in.radiance;
      }
      continue;
    }
    Light l;
    l.kind = in.kind;
    l.radiance = in.radiance;
    l.position = in.position.cast<float>();
    const Eigen::Matrix3f rotation = in.worldRotation.cast<float>();
    l.axisX = rotation.col(0).normalized();
    l.axisY = rotation.col(1).normalized();
    l.axisZ = rotation.col(2).normalized();
    l.emit = in.direction.cast<float>().normalized();
    l.radius = in.radius;
    l.width = in.width;
    l.height = in.height;
    l.length = in.length;
    l.diffuse = in.diffuse;
    l.specular = in.specular;
    anyLobeMultiplier_ = anyLobeMultiplier_ || in.diffuse != 1.0f || in.specular != 1.0f;
    const float L = std::max(luminance(l.radiance), 0.0f);
    double phi = 0;
    switch (in.kind) {
      case LightKind::Sphere:
        l.area = 4.0f * kPi * l.radius * l.radius;
        phi = double(L) * kPi * l.area;
        l.point = l.delta = in.treatAsPoint;
        break;
      case LightKind::Rect:
        l.area = l.width * l.height;
        phi = double(L) * kPi * l.area;
        break;
      case LightKind::Disk:
        l.area = kPi * l.radius * l.radius;
        phi = double(L) * kPi * l.area;
        break;
      case LightKind::Cylinder:
        l.area = 2.0f * kPi * l.radius * l.length;
        phi = double(L) * kPi * l.area;
        break;
      case LightKind::Distant: {
        l.toLight = -l.emit;
        const float halfAngle = std::clamp(in.angle, 0.0f, 180.0f) * 0.5f * kPi / 180.0f;
        l.delta = !(halfAngle > 0.0f);
        if (!l.delta) {
          const float s = std::sin(0.5f * halfAngle);
          l.oneMinusCos = 2.0f * s * s;
          l.sin2Half = std::sin(halfAngle) * std::sin(halfAngle);
          // Irradiance E at normal incidence from a cone of uniform radiance
          // L is L pi sin^2(half-angle).
          l.radiance = in.radiance / (kPi * l.sin2Half);
        }
        // What crosses a disk the size of the scene (pbrt-v4's DistantLight::Phi).
        phi = double(std::max(luminance(in.radiance), 0.0f)) * kPi * sceneRadius * sceneRadius;
        break;
      }
      case LightKind::Dome: break;
    }
    if (!(l.area > 0.0f) && in.kind != LightKind::Distant) continue;  // a light of no size sends nothing
    lights_.push_back(l);
    power.push_back(std::isfinite(phi) ? phi : 0.0);
  }
  if (anyDome) {
    const float mapPower = dome.map ? std::max(luminance(dome.mapScale.cwiseProduct(dome.map->mean)), 0.0f) : 0.0f;
    const float ambientPower = std::max(luminance(dome.ambient), 0.0f);
    dome.mapProbability = mapPower + ambientPower > 0.0f ? mapPower / (mapPower + ambientPower) : 0.0f;
    // A dome of radiance L around a scene of radius R: 4 pi^2 R^2 L (pbrt-v4).
    // A dome without a map is never picked for a shadow ray: it would be
    // sampled by the cosine over the hemisphere, which is what a diffuse
    // BSDF's own direction already draws (and a glossy one's does better),
    // so its light comes from the path's escaping rays alone, at full weight
    // (its light pdf is 0), and the shadow rays go to the lights that need
    // them. Under the demo's sky that was 39 % of the shadow rays.
    lights_.push_back(dome);
    const double domePower = dome.map ? double(mapPower + ambientPower) : 0.0;
    power.push_back(4.0 * kPi * kPi * sceneRadius * sceneRadius * domePower);
  }
  double total = 0;
  for (double p : power) total += p;
  pickCdf_.push_back(0.0f);
  double running = 0;
  for (size_t i = 0; i < lights_.size(); ++i) {
    running += power[i];
    lights_[i].pick = total > 0.0 ? float(power[i] / total) : 0.0f;
    pickCdf_.push_back(total > 0.0 ? float(running / total) : 0.0f);
  }
  if (total > 0.0) pickCdf_.back() = 1.0f;
}

bool PtLights::sample(const Vec3f& p, const Vec3f& n, float uPick, const Vec2f& u, LightSample& out) const {
  if (lights_.empty() || !(pickCdf_.back() > 0.0f)) return false;
  // The light whose share of the cdf holds uPick; what is left of uPick
  // inside that share is a fresh uniform number (for the dome's strategy).
  const auto above = std::upper_bound(pickCdf_.begin(), pickCdf_.end(), uPick);
  const size_t index = std::min(size_t(std::max<std::ptrdiff_t>(above - pickCdf_.begin() - 1, 0)), lights_.size() - 1);
  const Light& l = lights_[index];
  if (!(l.pick > 0.0f)) return false;
  const float uRest = std::clamp((uPick - pickCdf_[index]) / l.pick, 0.0f, 0x1.fffffep-1f);
  out.light = int(index);
  out.delta = false;
  switch (l.kind) {
    case LightKind::Sphere: {
      const Vec3f toCentre = l.position - p;
      const float d2 = toCentre.squaredNorm();
      const float r2 = l.radius * l.radius;
      if (l.point) {  // intensity L pi r^2: the irradiance it gives at distance d, head-on
        if (!(d2 > 0.0f)) return false;
        const float d = std::sqrt(d2);
        out.direction = toCentre / d;
        out.distance = d;
        out.radiance = l.radiance * (kPi * r2 / d2);
        out.pdf = l.pick;
        out.delta = true;
        break;
      }
      if (!(d2 > r2)) return false;  // inside the light: it emits outward only
      const float d = std::sqrt(d2);
      const float sin2Max = r2 / d2;
      const float cosMax = std::sqrt(std::max(0.0f, 1.0f - sin2Max));
      const float oneMinusCosMax = sin2Max / (1.0f + cosMax);
      const Vec3f axis = toCentre / d;
      out.direction = sampleCone(axis, oneMinusCosMax, u);
      // The near intersection with the sphere (or the tangent point when
      // rounding puts the direction just outside it).
      const float along = out.direction.dot(toCentre);
      const float disc = r2 - (d2 - along * along);
      out.distance = disc > 0.0f ? along - std::sqrt(disc) : std::sqrt(std::max(d2 - r2, 0.0f));
      out.radiance = l.radiance;
      out.pdf = l.pick / (2.0f * kPi * oneMinusCosMax);
      break;
    }
    case LightKind::Rect:
    case LightKind::Disk:
    case LightKind::Cylinder: {
      Vec3f q, normal;
      if (l.kind == LightKind::Rect) {
        q = l.position + (u.x() - 0.5f) * l.width * l.axisX + (u.y() - 0.5f) * l.height * l.axisY;
        normal = l.emit;
      } else if (l.kind == LightKind::Disk) {
        const Vec2f d = concentricDisk(u) * l.radius;
        q = l.position + d.x() * l.axisX + d.y() * l.axisY;
        normal = l.emit;
      } else {
        const float phi = 2.0f * kPi * u.y();
        normal = std::cos(phi) * l.axisY + std::sin(phi) * l.axisZ;
        q = l.position + (u.x() - 0.5f) * l.length * l.axisX + l.radius * normal;
      }
      const Vec3f toLight = q - p;
      const float d2 = toLight.squaredNorm();
      if (!(d2 > 0.0f)) return false;
      const float d = std::sqrt(d2);
      out.direction = toLight / d;
      const float cosLight = -normal.dot(out.direction);
      if (!(cosLight > 0.0f)) return false;  // the dark side faces p
      out.distance = d;
      out.radiance = l.radiance;
      // Area density to solid angle: d^2 / (A cos).
      out.pdf = l.pick * d2 / (l.area * cosLight);
      break;
    }
    case LightKind::Distant:
      if (l.delta) {
        out.direction = l.toLight;
        out.pdf = l.pick;
        out.delta = true;
      } else {
        out.direction = sampleCone(l.toLight, l.oneMinusCos, u);
        out.pdf = l.pick / (2.0f * kPi * l.oneMinusCos);
      }
      out.distance = kInf;
      out.radiance = l.radiance;
      break;
    case LightKind::Dome: {
      if (uRest < l.mapProbability) {
        const EnvironmentSample s = l.map->sampler.sample(u);
        out.direction = (l.domeFromWorld.transpose() * s.direction).normalized();
      } else {
        const Vec2f d = concentricDisk(u);
        const float z = std::sqrt(std::max(0.0f, 1.0f - d.squaredNorm()));
        out.direction = ShadingFrame::fromNormal(n).toWorld({d.x(), d.y(), z}).normalized();
      }
      out.distance = kInf;
      out.radiance = domeRadiance(l, out.direction);
      out.pdf = l.pick * densityOf(l, p, n, out.direction);
      break;
    }
  }
  return out.pdf > 0.0f && std::isfinite(out.pdf);
}

Vec3f PtLights::domeRadiance(const Light& l, const Vec3f& wi) const {
  Vec3f radiance = l.ambient;
  if (l.map) radiance += l.mapScale.cwiseProduct(l.map->radiance(l.domeFromWorld * wi));
  return radiance;
}

float PtLights::densityOf(const Light& l, const Vec3f& p, const Vec3f& n, const Vec3f& wi) const {
  switch (l.kind) {
    case LightKind::Sphere: {
      const Vec3f toCentre = l.position - p;
      const float d2 = toCentre.squaredNorm(), r2 = l.radius * l.radius;
      if (l.point || !(d2 > r2)) return 0.0f;
      const float sin2Max = r2 / d2;
      const float oneMinusCosMax = sin2Max / (1.0f + std::sqrt(std::max(0.0f, 1.0f - sin2Max)));
      return 1.0f / (2.0f * kPi * oneMinusCosMax);
    }
    case LightKind::Rect:
    case LightKind::Disk:
    case LightKind::Cylinder: {
      PtRay ray{p, wi, 0.0f, kInf};
      float t;
      if (!hitShape(l, ray, t)) return 0.0f;
      const Vec3f q = p + t * wi;
      Vec3f normal = l.emit;
      if (l.kind == LightKind::Cylinder) {
        const Vec3f radial = (q - l.position) - (q - l.position).dot(l.axisX) * l.axisX;
        normal = radial.normalized();
      }
      const float cosLight = -normal.dot(wi);
      return cosLight > 0.0f ? t * t / (l.area * cosLight) : 0.0f;
    }
    case LightKind::Distant: {
      if (l.delta) return 0.0f;
      const float sin2 = wi.cross(l.toLight).squaredNorm();
      return wi.dot(l.toLight) > 0.0f && sin2 <= l.sin2Half ? 1.0f / (2.0f * kPi * l.oneMinusCos) : 0.0f;
    }
    case LightKind::Dome: {
      float density = (1.0f - l.mapProbability) * std::max(0.0f, n.dot(wi)) / kPi;
      if (l.map && l.mapProbability > 0.0f) density += l.mapProbability * l.map->sampler.pdf(l.domeFromWorld * wi);
      return density;
    }
  }
  return 0.0f;
}

float PtLights::pdf(int light, const Vec3f& p, const Vec3f& n, const Vec3f& wi) const {
  const Light& l = lights_[size_t(light)];
  return l.pick * densityOf(l, p, n, wi);
}

bool PtLights::hitShape(const Light& l, const PtRay& ray, float& t) const {
  const Vec3f& o = ray.origin;
  const Vec3f& d = ray.direction;
  switch (l.kind) {
    case LightKind::Sphere: {
      if (l.point) return false;
      // From outside only: the near root is the emitting side.
      const Vec3f oc = o - l.position;
      const float r2 = l.radius * l.radius;
      const float c = oc.squaredNorm() - r2;
      if (!(c > 0.0f)) return false;
      const float b = oc.dot(d);
      if (b >= 0.0f) return false;  // moving away from the centre
      const float disc = r2 - (oc - b * d).squaredNorm();  // r^2 minus the squared distance of the line
      if (disc < 0.0f) return false;
      // The near root, as c / q to avoid the cancellation of -b - sqrt(disc).
      const float q = -b + std::sqrt(disc);
      t = c / q;
      return t > ray.tMin && t < ray.tMax;
    }
    case LightKind::Rect:
    case LightKind::Disk: {
      const float facing = d.dot(l.emit);
      if (!(facing < 0.0f)) return false;  // only rays that look at the emitting face
      t = (l.position - o).dot(l.emit) / facing;
      if (!(t > ray.tMin && t < ray.tMax)) return false;
      const Vec3f q = o + t * d - l.position;
      const float x = q.dot(l.axisX), y = q.dot(l.axisY);
      if (l.kind == LightKind::Rect) return std::abs(x) <= 0.5f * l.width && std::abs(y) <= 0.5f * l.height;
      return x * x + y * y <= l.radius * l.radius;
    }
    case LightKind::Cylinder: {
      // The infinite cylinder around the X axis, in the light's frame; the
      // entering root is the outer face.
      const Vec3f oc = o - l.position;
      const float oy = oc.dot(l.axisY), oz = oc.dot(l.axisZ), dy = d.dot(l.axisY), dz = d.dot(l.axisZ);
      const float a = dy * dy + dz * dz;
      if (!(a > 0.0f)) return false;
      const float b = oy * dy + oz * dz;
      const float c = oy * oy + oz * oz - l.radius * l.radius;
      if (!(c > 0.0f) || b >= 0.0f) return false;  // inside, or moving away from the axis
      const float disc = b * b - a * c;
      if (disc < 0.0f) return false;
      t = c / (-b + std::sqrt(disc));
      if (!(t > ray.tMin && t < ray.tMax)) return false;
      return std::abs((oc + t * d).dot(l.axisX)) <= 0.5f * l.length;
    }
    default: return false;
  }
}

bool PtLights::intersect(const PtRay& ray, LightHit& hit) const {
  hit.light = -1;
  PtRay r = ray;
  for (size_t i = 0; i < lights_.size(); ++i) {
    float t;
    if (!hitShape(lights_[i], r, t)) continue;
    hit.light = int(i);
    hit.t = t;
    hit.radiance = lights_[i].radiance;
    r.tMax = t;  // only a nearer one can win now
  }
  return hit.light >= 0;
}

bool PtLights::blocks(const PtRay& ray, int except) const {
  for (size_t i = 0; i < lights_.size(); ++i) {
    float t;
    if (int(i) != except && hitShape(lights_[i], ray, t)) return true;
  }
  return false;
}

Vec3f PtLights::response(int light, const BsdfLobes& f) const {
  const Light& l = lights_[size_t(light)];
  return l.diffuse * f.diffuse + l.specular * f.specular;
}

Vec3f PtLights::responseScale(int light, const BsdfLobes& f) const {
  const Vec3f sum = f.diffuse + f.specular, weighted = response(light, f);
  Vec3f scale;
  for (int c = 0; c < 3; ++c) scale[c] = sum[c] > 0.0f ? weighted[c] / sum[c] : 1.0f;
  return scale;
}

Vec3f PtLights::escaped(const Vec3f& p, const Vec3f& n, const Vec3f& wi, float bsdfPdf, const BsdfLobes* lobes) const {
  Vec3f sum = Vec3f::Zero();
  for (size_t i = 0; i < lights_.size(); ++i) {
    const Light& l = lights_[i];
    Vec3f radiance;
    if (l.kind == LightKind::Dome) {
      radiance = domeRadiance(l, wi);
    } else if (l.kind == LightKind::Distant && !l.delta) {
      if (!(wi.dot(l.toLight) > 0.0f && wi.cross(l.toLight).squaredNorm() <= l.sin2Half)) continue;
      radiance = l.radiance;
    } else {
      continue;
    }
    const float weight = bsdfPdf > 0.0f ? powerHeuristic(bsdfPdf, l.pick * densityOf(l, p, n, wi)) : 1.0f;
    if (lobes && (l.diffuse != 1.0f || l.specular != 1.0f))
      radiance = radiance.cwiseProduct(responseScale(int(i), *lobes));
    sum += weight * radiance;
  }
  return sum;
}

}  // namespace sdg
