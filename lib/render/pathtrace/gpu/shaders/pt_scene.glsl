// Part 3: the scene. Geometry (embree_scene.cpp's geometry()), materials
// and textures (pt_materials.cpp, pt_textures.cpp), and the traversal of
// the two-level BVH that gpu_bvh.cpp builds with Embree's BVH builder:
// 4-wide nodes holding their children's boxes, a top level over the
// instances, one bottom level per distinct mesh.

// A 4-wide node: the children's boxes as structure-of-arrays rows, and the
// children: >= 0 an inner node (index from the level's base), kEmptyChild
// no child, otherwise a leaf ~(first << 4 | count - 1).
struct Node {
  vec4 loX, hiX, loY, hiY, loZ, hiZ;
  ivec4 child;
};
const int kEmptyChild = 0x7fffffff;
layout(std430, binding = 2) readonly buffer Nodes { Node nodes[]; };           // the meshes' levels
layout(std430, binding = 3) readonly buffer TopNodes { Node topNodes[]; };    // the frame's level over the instances
// Triangles in leaf order, four rows each: the unit-triangle map's rows u, v and z (gpu_scene.cpp's
// unitTriangle, mesh space), then the mesh's own triangle index (x, as a float: exact below 2^24).
layout(std430, binding = 4) readonly buffer Triangles { vec4 triangles[]; };
// Vertices: position (w: u), normal (w: v); a mesh's vertex colours (rgb,
// opacity) follow its vertices when it has them (Mesh.flags.w).
layout(std430, binding = 5) readonly buffer Vertices { vec4 vertices[]; };
// Per triangle in the mesh's own order: its three vertex indices and its part.
layout(std430, binding = 6) readonly buffer Indices { uvec4 indices[]; };
struct Mesh {
  ivec4 bases;  // nodes, leaf-order triangles, indices, vertices
  ivec4 flags;  // has normals, has uvs, root item (0, or a leaf code when the whole mesh is one leaf),
                // vertex colours (their first vec4 in vertices + 1; 0: none)
};
layout(std430, binding = 7) readonly buffer Meshes { Mesh meshes[]; };
struct Instance {
  vec4 world[3];   // rows of world from local
  vec4 local[3];   // rows of local from world
  vec4 normal[3];  // rows of the normal matrix
  ivec4 ids;       // mesh, first material, material count, instance id
  ivec4 flags;     // cut-out, -, -, -
};
layout(std430, binding = 8) readonly buffer Instances { Instance instances[]; };
struct Material {
  vec4 baseColor;   // rgb, roughness
  vec4 scalars;     // metallic, roughness influence, metallic influence, normal scale
  vec4 opacity;     // constant, cut-off, cos rotate, sin rotate
  vec4 placement;   // texture scale xy, specular level, -
  ivec4 maps;       // base, roughness, metallic, normal (-1: none)
  ivec4 mapInfo;    // opacity map, roughness channel, metallic channel, opacity source (0 none, 1 constant, 2 map, 3 base alpha)
  ivec4 modes;      // part material, triplanar, vertex colours, -
};
layout(std430, binding = 9) readonly buffer Materials { Material materials[]; };
layout(std430, binding = 10) readonly buffer TextureTable { ivec4 textures[]; };  // first texel, width, height, sRGB
layout(std430, binding = 11) readonly buffer Texels { uint texels[]; };  // RGBA8 texels; a dome's as 4 float words

// --- Textures: PtTexture::sample ---
vec4 texel(ivec4 t, uint x, uint y) {
  uint p = texels[uint(t.x) + y * uint(t.y) + x];
  uvec4 c = uvec4(p & 255u, (p >> 8) & 255u, (p >> 16) & 255u, p >> 24);
  if (t.w != 0) return vec4(params.tables[c.x], params.tables[c.y], params.tables[c.z], float(c.w) * (1.0 / 255.0));
  return vec4(c) * (1.0 / 255.0);
}
uint wrapIndex(int i, int size) {
  int m = i % size;
  return uint(m < 0 ? m + size : m);
}
vec4 sampleTexture(int index, vec2 uv) {
  ivec4 t = textures[index];
  if (isnan(uv.x) || isinf(uv.x) || isnan(uv.y) || isinf(uv.y)) return texel(t, 0u, 0u);
  float x = (uv.x - floor(uv.x)) * float(t.y) - 0.5;
  float y = (uv.y - floor(uv.y)) * float(t.z) - 0.5;
  float fx = floor(x), fy = floor(y);
  float ax = x - fx, ay = y - fy;
  int ix = int(fx), iy = int(fy);
  uint x0 = wrapIndex(ix, t.y), x1 = wrapIndex(ix + 1, t.y);
  uint y0 = wrapIndex(iy, t.z), y1 = wrapIndex(iy + 1, t.z);
  return (texel(t, x0, y0) * (1.0 - ax) + texel(t, x1, y0) * ax) * (1.0 - ay) +
         (texel(t, x0, y1) * (1.0 - ax) + texel(t, x1, y1) * ax) * ay;
}

// --- Geometry: EmbreeScene::geometry ---
struct Geometry {
  vec3 position, geometricNormal, shadingNormal;
  vec2 uv;
  vec3 edge1, edge2;
  vec2 uvEdge1, uvEdge2;
  uint part;
  vec4 color;  // the mesh's vertex colour (rgb, opacity) interpolated; white without
};
vec3 rowsTimes(vec4 rows[3], vec3 p, float w) {
  vec4 h = vec4(p, w);
  return vec3(dot(rows[0], h), dot(rows[1], h), dot(rows[2], h));
}
Geometry surfaceGeometry(uint instance, uint triangle, float u, float v) {
  Instance inst = instances[instance];
  Mesh mesh = meshes[inst.ids.x];
  uvec4 tri = indices[uint(mesh.bases.z) + triangle];
  uint vb = uint(mesh.bases.w);
  vec4 a0 = vertices[2u * (vb + tri.x)], a1 = vertices[2u * (vb + tri.y)], a2 = vertices[2u * (vb + tri.z)];
  float w = 1.0 - u - v;
  Geometry g;
  vec3 p0 = rowsTimes(inst.world, a0.xyz, 1.0), p1 = rowsTimes(inst.world, a1.xyz, 1.0), p2 = rowsTimes(inst.world, a2.xyz, 1.0);
  g.position = w * p0 + u * p1 + v * p2;
  g.edge1 = p1 - p0;
  g.edge2 = p2 - p0;
  vec3 c = cross(g.edge1, g.edge2);
  float cn = length(c);
  g.geometricNormal = cn > 0.0 ? c / cn : vec3(0.0, 0.0, 1.0);
  g.shadingNormal = g.geometricNormal;
  if (mesh.flags.x != 0) {
    vec4 b0 = vertices[2u * (vb + tri.x) + 1u], b1 = vertices[2u * (vb + tri.y) + 1u], b2 = vertices[2u * (vb + tri.z) + 1u];
    vec3 n = rowsTimes(inst.normal, w * b0.xyz + u * b1.xyz + v * b2.xyz, 0.0);
    float len = length(n);
    if (len > 0.0 && !isinf(len) && !isnan(len)) g.shadingNormal = n / len;
  }
  if (mesh.flags.y != 0) {
    vec2 t0 = vec2(a0.w, vertices[2u * (vb + tri.x) + 1u].w), t1 = vec2(a1.w, vertices[2u * (vb + tri.y) + 1u].w),
         t2 = vec2(a2.w, vertices[2u * (vb + tri.z) + 1u].w);
    g.uv = w * t0 + u * t1 + v * t2;
    g.uvEdge1 = t1 - t0;
    g.uvEdge2 = t2 - t0;
  } else {
    g.uv = g.uvEdge1 = g.uvEdge2 = vec2(0.0);
  }
  g.part = tri.w;
  g.color = vec4(1.0);
  if (kVertexColors && mesh.flags.w > 0) {
    uint cb = uint(mesh.flags.w - 1);
    g.color = w * vertices[cb + tri.x] + u * vertices[cb + tri.y] + v * vertices[cb + tri.z];
  }
  return g;
}

// --- Materials: pt_materials.cpp ---
Material materialOf(uint instance, uint part) {
  ivec4 ids = instances[instance].ids;
  return materials[ids.y + min(int(part), ids.z - 1)];
}
vec2 transformUv(Material m, vec2 uv) {
  vec2 s = uv * m.placement.xy;
  return vec2(m.opacity.z * s.x - m.opacity.w * s.y, m.opacity.w * s.x + m.opacity.z * s.y);
}
// Written as loops around one texture read, each read once in the
// compiled kernel: GLSL inlines every call, and the kernel's size is what
// a driver's compile time (llvmpipe's above all) grows with.
vec4 sampleMap(Material m, int map, Geometry g, vec3 n) {
  bool triplanar = kTriplanar && m.modes.y != 0;
  vec3 w = abs(n);
  w /= (w.x + w.y + w.z);
  vec3 p = g.position;
  vec4 sum = vec4(0.0);
  for (int k = 0; k < (triplanar ? 3 : 1); ++k) {
    // A projection of weight 0 adds exactly nothing (the texels are finite):
    // on a floor or a wall square to the axes, two of the three.
    if (triplanar && w[k] == 0.0) continue;
    vec2 uv = !triplanar ? g.uv : (k == 0 ? p.yz : (k == 1 ? p.xz : p.xy));
    vec4 t = sampleTexture(map, transformUv(m, uv));
    sum = k == 0 ? (triplanar ? t * w.x : t) : sum + t * w[k];
  }
  return sum;
}
vec3 mappedNormal(Material m, Geometry g, vec3 n) {
  vec2 duv1 = transformUv(m, g.uvEdge1), duv2 = transformUv(m, g.uvEdge2);
  vec3 perp2 = cross(g.edge2, n), perp1 = cross(n, g.edge1);
  vec3 t = perp2 * duv1.x + perp1 * duv2.x;
  vec3 b = perp2 * duv1.y + perp1 * duv2.y;
  if (dot(n, cross(g.edge1, g.edge2)) < 0.0) {
    t = -t;
    b = -b;
  }
  float longest2 = max(dot(t, t), dot(b, b));
  float scale = 1.0 / sqrt(max(longest2, 1e-20));
  vec4 tx = sampleTexture(m.maps.w, transformUv(m, g.uv));
  float ns = m.scalars.w;
  vec3 tilt = vec3(ns * (2.0 * tx.x - 1.0), ns * (2.0 * tx.y - 1.0), 2.0 * tx.z - 1.0);
  vec3 mapped = t * (scale * tilt.x) - b * (scale * tilt.y) + n * tilt.z;
  float length2 = dot(mapped, mapped);
  return length2 > 1e-12 && !isinf(length2) && !isnan(length2) ? mapped / sqrt(length2) : n;
}
bool surfaceOpaque(Material m, Geometry g) {
  float o = m.opacity.x;
  int source = kOpacity ? m.mapInfo.w : 0;
  if (source == 0) return true;
  if (source >= 2) {
    vec4 t = sampleMap(m, source == 2 ? m.mapInfo.x : m.maps.x, g, g.shadingNormal);
    o *= source == 2 ? t.x : t.w;
  }
  if (kVertexColors && m.modes.z != 0) o *= g.color.w;
  return o >= m.opacity.y;
}
struct Shaded {
  vec3 baseColor;
  float metallic, roughness, specularLevel;
  vec3 normal, albedo;
};
Shaded shadeSurface(Material m, Geometry g, vec3 towardViewer) {
  vec3 n = dot(g.shadingNormal, towardViewer) < 0.0 ? -g.shadingNormal : g.shadingNormal;
  float roughness = m.baseColor.w, metallic = m.scalars.x;
  bool part = m.modes.x != 0;
  Shaded s;
  s.albedo = m.baseColor.xyz;
  // The roughness, metallic and base colour maps, in one loop (see sampleMap);
  // the loop covers only the kinds of map the stage has.
  for (int k = kSurfaceMaps ? 0 : 2; k < (kBaseColorMaps ? 3 : 2); ++k) {
    int map = k == 0 ? m.maps.y : (k == 1 ? m.maps.z : m.maps.x);
    if (map < 0) continue;
    vec4 t = sampleMap(m, map, g, n);
    if (k == 0) {
      float v = t[m.mapInfo.y];
      roughness = part ? roughness * v : roughness + (v - roughness) * m.scalars.y;
    } else if (k == 1) {
      float v = t[m.mapInfo.z];
      metallic = part ? metallic * v : metallic + (v - metallic) * m.scalars.z;
    } else {
      s.albedo = t.xyz;
    }
  }
  if (kVertexColors && m.modes.z != 0) s.albedo *= g.color.rgb;
  s.baseColor = s.albedo;
  s.roughness = clamp(roughness, 0.0, 1.0);
  s.metallic = clamp(metallic, 0.0, 1.0);
  s.specularLevel = m.placement.z;
  if (kNormalMaps && m.maps.w >= 0) n = mappedNormal(m, g, n);
  const float kMinCosine = 0.01;
  float c = dot(n, towardViewer);
  if (c < kMinCosine) n = normalize(n + (kMinCosine - c) * towardViewer);
  s.normal = n;
  return s;
}

// --- Traversal ---
struct Hit {
  uint instance, triangle;
  float u, v, t;
};

// The entry distance of the ray into the four boxes (kInf where missed).
// The far distance is pushed out by a few ulps, as robust traversal does,
// so a box of zero thickness (a plane) is still entered. Each slab is one
// fused multiply-add, lo * inv + (-o * inv): `inv` comes from safeInverse,
// so a zero direction component never makes that inf - inf.
vec4 boxEntry(Node n, vec3 o, vec3 inv, float tMin, float tMax) {
  vec3 oi = -o * inv;
  vec4 tx0 = fma(n.loX, vec4(inv.x), vec4(oi.x)), tx1 = fma(n.hiX, vec4(inv.x), vec4(oi.x));
  vec4 ty0 = fma(n.loY, vec4(inv.y), vec4(oi.y)), ty1 = fma(n.hiY, vec4(inv.y), vec4(oi.y));
  vec4 tz0 = fma(n.loZ, vec4(inv.z), vec4(oi.z)), tz1 = fma(n.hiZ, vec4(inv.z), vec4(oi.z));
  vec4 tNear = max(max(min(tx0, tx1), min(ty0, ty1)), max(min(tz0, tz1), vec4(tMin)));
  vec4 tFar = min(min(max(tx0, tx1), max(ty0, ty1)), min(max(tz0, tz1), vec4(tMax))) * 1.0000004;
  bvec4 entered = bvec4(tNear.x <= tFar.x, tNear.y <= tFar.y, tNear.z <= tFar.z, tNear.w <= tFar.w);
  bvec4 present = notEqual(n.child, ivec4(kEmptyChild));
  return mix(vec4(kInf), tNear, bvec4(entered.x && present.x, entered.y && present.y, entered.z && present.z,
                                      entered.w && present.w));
}
// 1 / d with no infinity: a zero component becomes 1e-20 first (as Embree's
// safe reciprocal does), so the fused slabs above never meet inf - inf.
vec3 safeInverse(vec3 d) { return 1.0 / mix(d, vec3(1e-20), lessThan(abs(d), vec3(1e-20))); }

// Orders two (entry, child) pairs nearest first: a step of the sorting network below.
#define SDG_ORDER(ta, ca, tb, cb) \
  if (tb < ta) {                  \
    float t_ = ta;                \
    ta = tb;                      \
    tb = t_;                      \
    int c_ = ca;                  \
    ca = cb;                      \
    cb = c_;                      \
  }

// The unit-triangle test (gpu_scene.cpp's unitTriangle): the ray taken
// into the triangle's own space, where it lies at z = 0 and spans u, v >= 0,
// u + v <= 1; u and v are Embree's barycentrics (p = (1-u-v) p0 + u p1 + v p2).
bool hitTriangle(vec3 o, vec3 d, vec4 rowU, vec4 rowV, vec4 rowZ, float tMin, float tMax, out float t, out float u, out float v) {
  t = -(dot(rowZ.xyz, o) + rowZ.w) / dot(rowZ.xyz, d);
  u = v = 0.0;
  if (!(t > tMin && t < tMax)) return false;
  u = dot(rowU.xyz, o) + rowU.w + t * dot(rowU.xyz, d);
  if (u < 0.0 || u > 1.0) return false;
  v = dot(rowV.xyz, o) + rowV.w + t * dot(rowV.xyz, d);
  return v >= 0.0 && u + v <= 1.0;
}

bool opaqueAt(uint instance, uint triangle, float u, float v) {
  Geometry g = surfaceGeometry(instance, triangle, u, v);
  return surfaceOpaque(materialOf(instance, g.part), g);
}

const int kStackSize = 64;
// A stack entry that enters instance (entry - kEnterInstance): the rest of
// a top-level leaf's instances wait on the stack as these. Node indices
// stay below it.
const int kEnterInstance = 0x40000000;

// The closest hit (or, with anyHit, any hit) of the two-level BVH over one
// stack: the top level's entries, then, above the stack height where an
// instance was entered, that instance's mesh's, with the ray taken into the
// mesh's space unnormalised (so t is the same in both). One stack and one
// node loop for both levels, not loops per level: half the local memory,
// and the warp's invocations stay in the same loop whatever level each is
// in. Counted in the pixel's ray counter by the callers.
bool traceScene(vec3 o, vec3 d, float tMin, float tMax, bool anyHit, out Hit hit) {
  hit.instance = hit.triangle = 0u;
  hit.u = hit.v = hit.t = 0.0;
  if (params.counts.z == 0) return false;
  vec3 ro = o, rd = d, inv = safeInverse(d);
  int stack[kStackSize];
  int top = 0;
  // The item visited next, kept out of the stack (the nearest child, a
  // mesh's root): a store and a load of local memory less per node.
  int item = int(params.seed.z);
  int instance = -1, instanceBase = 0, nodeBase = 0, triBase = 0;
  bool cutOut = false, found = false;
  for (;;) {
    // Inner nodes of either level, until the item is a leaf or an instance
    // to enter: a warp's invocations walk nodes together, then test
    // triangles together (Aila and Laine's "while-while"), instead of each
    // iteration running the node and the leaf code for a mixed warp.
    for (;;) {
      if (item == kEmptyChild) {
        if (instance >= 0 && top == instanceBase) {  // the mesh is done: back to the top level
          instance = -1;
          ro = o;
          rd = d;
          inv = safeInverse(d);
        }
        if (top == 0) break;
        item = stack[--top];
      }
      if (item < 0 || (instance < 0 && item >= kEnterInstance)) break;  // a leaf or an instance to enter
      Node n = instance < 0 ? topNodes[item] : nodes[nodeBase + item];
      vec4 entry = boxEntry(n, ro, inv, tMin, tMax);
      // The children sorted by entry distance (a five-step network, no
      // indexing by a variable); the nearest is visited next, the others
      // pushed farthest first; missed ones (kInf) sort last and are dropped.
      float t0 = entry.x, t1 = entry.y, t2 = entry.z, t3 = entry.w;
      int c0 = n.child.x, c1 = n.child.y, c2 = n.child.z, c3 = n.child.w;
      SDG_ORDER(t0, c0, t1, c1)
      SDG_ORDER(t2, c2, t3, c3)
      SDG_ORDER(t0, c0, t2, c2)
      SDG_ORDER(t1, c1, t3, c3)
      SDG_ORDER(t1, c1, t2, c2)
      if (t3 < kInf && top < kStackSize) stack[top++] = c3;
      if (t2 < kInf && top < kStackSize) stack[top++] = c2;
      if (t1 < kInf && top < kStackSize) stack[top++] = c1;
      item = t0 < kInf ? c0 : kEmptyChild;
    }
    if (item == kEmptyChild) break;  // the stack is empty: done
    if (instance >= 0) {  // a mesh's leaf
      int code = ~item;
      int first = code >> 4, count = (code & 15) + 1;
      for (int k = 0; k < count; ++k) {
        int at = 4 * (triBase + first + k);
        float t, u, v;
        if (!hitTriangle(ro, rd, triangles[at], triangles[at + 1], triangles[at + 2], tMin, tMax, t, u, v)) continue;
        uint triangle = uint(triangles[at + 3].x);
        if (cutOut && !opaqueAt(uint(instance), triangle, u, v)) continue;
        tMax = t;
        hit.instance = uint(instance);
        hit.triangle = triangle;
        hit.u = u;
        hit.v = v;
        hit.t = t;
        found = true;
        if (anyHit) return true;
      }
      item = kEmptyChild;
      continue;
    }
    int enter;
    if (item >= kEnterInstance) {
      enter = item - kEnterInstance;
    } else {  // a top-level leaf: its instances (stored in leaf order)
      int code = ~item;
      int first = code >> 4, count = (code & 15) + 1;
      for (int k = count - 1; k >= 1; --k)
        if (top < kStackSize) stack[top++] = kEnterInstance + first + k;
      enter = first;
    }
    // Enter instance `enter`: its mesh's root above the current stack.
    Instance inst = instances[enter];
    Mesh mesh = meshes[inst.ids.x];
    instance = enter;
    cutOut = kOpacity && inst.flags.x != 0;
    ro = rowsTimes(inst.local, o, 1.0);
    rd = rowsTimes(inst.local, d, 0.0);
    inv = safeInverse(rd);
    nodeBase = mesh.bases.x;
    triBase = mesh.bases.y;
    instanceBase = top;
    item = mesh.flags.z;
  }
  return found;
}
