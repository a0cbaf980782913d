// carbtf's material for any fragment shader: a host engine includes this file (with carbtf_gpu_shared.h
// on its include path), binds MaterialBinding's descriptor set at CARBTF_MATERIAL_SET, and calls
// carbtf_material_shade() per light (from one carbtf_material_surface() under several lights). Its own
// pipeline layout puts MaterialBinding::set_layout() there, and its pipeline takes the specialization
// constants MaterialBinding::shader_constants() gives.
//
// Directions are in the surface's tangent frame: x along +u (texture right), y towards texture row 0
// (texture up, i.e. minus the v direction), z along the normal. Texture coordinates (u, v) in [0, 1]^2
// cover the synthesized block once, v = 0 at row 0. Outside that the edge texels repeat, unless the
// textures are periodic (MaterialTablesHeader::wrap, for closed meshes): then addresses wrap.
//
// Per fragment: parallax occlusion (a ray march through the enlarged range map), the
// 9-weight (or 5-pair staircase) interpolation of the subspace images (docs/design.md 4.5) through precomputed lookup grids
// (a fixed, short list of candidates per grid cell: no search over the direction set), times the range
// map relit for the light, hidden where the relief casts a shadow (the material's shadow scale above
// 0), plus its specular lobe; the colour's brightness from the relief at the fragment's level, its chroma
// from the relief RangeTiles::chroma_levels mip levels above (the header's relief_chroma_levels). The CPU
// twin is analysis/reference/src/render_reference.cpp.
#ifndef CARBTF_MATERIAL_GLSL
#define CARBTF_MATERIAL_GLSL

#include "carbtf_gpu_shared.h"

#ifndef CARBTF_MATERIAL_SET
#define CARBTF_MATERIAL_SET 0
#endif

layout(set = CARBTF_MATERIAL_SET, binding = CARBTF_MATERIAL_BINDING_SUBSPACES) uniform sampler2DArray carbtf_subspaces;
layout(set = CARBTF_MATERIAL_SET, binding = CARBTF_MATERIAL_BINDING_RANGE) uniform sampler2DArray carbtf_range;
layout(std430, set = CARBTF_MATERIAL_SET, binding = CARBTF_MATERIAL_BINDING_TABLES) readonly buffer CarbtfTables {
  MaterialTablesHeader carbtf_header;
};
// The same buffer as 16-byte texels. The header's fields are read at one address by every fragment;
// the tables after it at addresses that vary per fragment, through texel fetches, which lavapipe
// gathers at a fraction of the cost of storage buffer reads.
layout(set = CARBTF_MATERIAL_SET, binding = CARBTF_MATERIAL_BINDING_TABLE_QUADS) uniform usamplerBuffer carbtf_table_quads;

uvec4 carbtf_table_quad(uint quad) {
  return texelFetch(carbtf_table_quads, int(quad));
}

// Specialization constant: false compiles the relief's cast shadows out (no horizon reads), for a
// pipeline that only draws materials without them (MaterialBinding::casts_shadows()); true, the default,
// is right for any material (the tables' header says whether this one casts shadows). A host whose own
// shader uses constant id CARBTF_SHADOWS_CONSTANT_ID defines it to another id before this include.
#ifndef CARBTF_SHADOWS_CONSTANT_ID
#define CARBTF_SHADOWS_CONSTANT_ID CARBTF_SHADOWS_DEFAULT_CONSTANT_ID
#endif
layout(constant_id = CARBTF_SHADOWS_CONSTANT_ID) const bool carbtf_shadows_compiled = true;

// Specialization constant: true reads the subspace images, and the range texture's heights, normals,
// tone and horizons, with textureLod() through the binding's sampler (trilinear, clamped or repeating as
// the textures are): one filtered read where the hand filtering reads eight texels. The fast path, for a
// binding whose sampler filters (MaterialBinding::hardware_filtering()). Its weights have the device's
// sub-texel precision, so the picture differs from the CPU twin's by up to that; false, the default,
// filters by hand with the twin's arithmetic. The normals keep the blend of their lengths either way
// (carbtf_relief(): the normal layer's w holds each texel's length).
#ifndef CARBTF_HARDWARE_FILTERING_CONSTANT_ID
#define CARBTF_HARDWARE_FILTERING_CONSTANT_ID CARBTF_HARDWARE_FILTERING_DEFAULT_CONSTANT_ID
#endif
layout(constant_id = CARBTF_HARDWARE_FILTERING_CONSTANT_ID) const bool carbtf_hardware_filtering = false;

// Specialization constant: how the light's and the view's 3 weights combine into pair weights
// (PairCoupling, direction_interpolation.hpp): CARBTF_PAIR_COUPLING_PRODUCT, the default, the paper's 9
// pairs; CARBTF_PAIR_COUPLING_STAIRCASE at most 5, so 5 subspace image reads per light instead of 9.
#ifndef CARBTF_PAIR_COUPLING_CONSTANT_ID
#define CARBTF_PAIR_COUPLING_CONSTANT_ID CARBTF_PAIR_COUPLING_DEFAULT_CONSTANT_ID
#endif
layout(constant_id = CARBTF_PAIR_COUPLING_CONSTANT_ID) const uint carbtf_pair_coupling = CARBTF_PAIR_COUPLING_PRODUCT;

// Specialization constant: carbtf_gpu_shared.h's CARBTF_COST_PROBE_* bits, for benchmarks only; 0 draws
// the material, and compiles every probe out.
#ifndef CARBTF_COST_PROBE_CONSTANT_ID
#define CARBTF_COST_PROBE_CONSTANT_ID CARBTF_COST_PROBE_DEFAULT_CONSTANT_ID
#endif
layout(constant_id = CARBTF_COST_PROBE_CONSTANT_ID) const uint carbtf_cost_probe = 0u;

bool carbtf_probed(uint part) {
  return (carbtf_cost_probe & part) != 0u;
}

const float CARBTF_PI = 3.14159265358979;

// Bilinear filtering by hand (texelFetch), edge texels repeated: the same arithmetic as the CPU
// reference, and it works for RGBA32F on devices without linear filtering of 32-bit floats.
struct CarbtfBilinear {
  ivec2 i0;
  ivec2 i1;
  vec2 f;
};

// At mip level `level` (its size is the full size halved `level` times, exactly: mip_chain.hpp).
CarbtfBilinear carbtf_bilinear(vec2 uv, int level) {
  ivec2 size = ivec2(int(carbtf_header.width), int(carbtf_header.height)) >> level;
  bool wrap = carbtf_header.wrap != 0u;
  // Periodic: the fractional part (x - floor(x) is exact), so the texel row and column stay in
  // [-1, size - 1] and only the ends wrap.
  vec2 u = wrap ? uv - floor(uv) : uv;
  vec2 t = u * vec2(size) - 0.5;
  vec2 base = floor(t);
  CarbtfBilinear b;
  b.f = t - base;
  ivec2 i = ivec2(clamp(base, vec2(-1.0), vec2(size)));
  if (wrap) {
    b.i0 = ivec2(i.x < 0 ? size.x - 1 : i.x, i.y < 0 ? size.y - 1 : i.y);
    b.i1 = ivec2(i.x + 1 >= size.x ? 0 : i.x + 1, i.y + 1 >= size.y ? 0 : i.y + 1);
  } else {
    b.i0 = clamp(i, ivec2(0), size - 1);
    b.i1 = clamp(i + 1, ivec2(0), size - 1);
  }
  return b;
}

vec3 carbtf_subspace_texel(CarbtfBilinear b, uint layer, int level) {
  int l = int(layer);
  vec3 top = mix(texelFetch(carbtf_subspaces, ivec3(b.i0.x, b.i0.y, l), level).rgb,
                 texelFetch(carbtf_subspaces, ivec3(b.i1.x, b.i0.y, l), level).rgb, b.f.x);
  vec3 bottom = mix(texelFetch(carbtf_subspaces, ivec3(b.i0.x, b.i1.y, l), level).rgb,
                    texelFetch(carbtf_subspaces, ivec3(b.i1.x, b.i1.y, l), level).rgb, b.f.x);
  return mix(top, bottom, b.f.y);
}

// The range texture's layer 0 (the height in texels) bilinearly at b of mip level `level`.
float carbtf_height_texel(CarbtfBilinear b, int level) {
  float top = mix(texelFetch(carbtf_range, ivec3(b.i0.x, b.i0.y, 0), level).r,
                  texelFetch(carbtf_range, ivec3(b.i1.x, b.i0.y, 0), level).r, b.f.x);
  float bottom = mix(texelFetch(carbtf_range, ivec3(b.i0.x, b.i1.y, 0), level).r,
                     texelFetch(carbtf_range, ivec3(b.i1.x, b.i1.y, 0), level).r, b.f.x);
  return mix(top, bottom, b.f.y);
}

// A level of detail split into the mip level below it and the share of the next level up: trilinear
// filtering. The share is 0 at integer levels, where one level is read.
struct CarbtfLod {
  int level;
  float t;
};

CarbtfLod carbtf_split_lod(float lod) {
  CarbtfLod s;
  s.level = int(floor(lod));
  s.t = lod - float(s.level);
  return s;
}

// The mip level a fragment at texture coordinate uv reads: log2 of the longer of its footprints along
// the screen's x and y, in texels (fine derivatives: the pixel's own 2 x 2 quad row and column),
// within [0, levels - 1]. 0 where a texel covers a pixel or more, so a close-up reads level 0 only.
// Call it in uniform control flow (it takes derivatives), with the mesh's uv before parallax.
float carbtf_material_lod(vec2 uv) {
  vec2 size = vec2(float(carbtf_header.width), float(carbtf_header.height));
  vec2 dx = dFdxFine(uv) * size, dy = dFdyFine(uv) * size;
  float footprint = max(dot(dx, dx), dot(dy, dy));
  float top = float(max(carbtf_header.mip_levels, 1u) - 1u);
  return footprint > 1.0 ? min(0.5 * log2(footprint), top) : 0.0;
}

// The range map's height at uv, in texels, its mean removed.
float carbtf_height(vec2 uv, float lod) {
  if (carbtf_hardware_filtering) return textureLod(carbtf_range, vec3(uv, 0.0), lod).r - carbtf_header.range_mean;
  CarbtfLod s = carbtf_split_lod(lod);
  float value = carbtf_height_texel(carbtf_bilinear(uv, s.level), s.level);
  if (s.t > 0.0) value = mix(value, carbtf_height_texel(carbtf_bilinear(uv, s.level + 1), s.level + 1), s.t);
  return value - carbtf_header.range_mean;
}
float carbtf_height(vec2 uv) {
  return carbtf_height(uv, 0.0);
}

// The relief at a point (tangent frame): the filtered normal of the range map (relief_normals.hpp;
// unit at level 0, shorter above where the facets under the footprint differ, which dims the relit
// factor as their own mean would), and the relief tone of each colour channel, the factor on the smooth
// texture's colour that follows the relief (the material's tone chroma applied).
struct CarbtfRelief {
  vec3 normal;
  float normal_length;  // the normal's length: the blend of the texels' lengths (carbtf_relief())
  vec3 tone;
  vec4 horizon_a;  // horizon tangents of azimuths 0-3 and 4-7 (relief_horizons.hpp)
  vec4 horizon_b;
};

// Layer `layer` of the range texture bilinearly at b of mip level `level`.
vec4 carbtf_range_texel(CarbtfBilinear b, int layer, int level) {
  vec4 top = mix(texelFetch(carbtf_range, ivec3(b.i0.x, b.i0.y, layer), level),
                 texelFetch(carbtf_range, ivec3(b.i1.x, b.i0.y, layer), level), b.f.x);
  vec4 bottom = mix(texelFetch(carbtf_range, ivec3(b.i0.x, b.i1.y, layer), level),
                    texelFetch(carbtf_range, ivec3(b.i1.x, b.i1.y, layer), level), b.f.x);
  return mix(top, bottom, b.f.y);
}

// The range texture bilinearly at b of mip level `level`: the normal from layer 1 (xyz, and its length
// in w, unblended: carbtf_relief() scales the blend), the tone from layer 0's gba, the horizons from
// layers 2 and 3.
CarbtfRelief carbtf_relief_texel(CarbtfBilinear b, int level) {
  CarbtfRelief relief;
  vec4 normal = carbtf_range_texel(b, 1, level);
  relief.normal = normal.xyz;
  relief.normal_length = normal.w;
  relief.tone = carbtf_range_texel(b, 0, level).yzw;
  relief.horizon_a = vec4(0.0);
  relief.horizon_b = vec4(0.0);
  if (!carbtf_shadows_compiled) return relief;
  relief.horizon_a = carbtf_range_texel(b, 2, level);
  relief.horizon_b = carbtf_range_texel(b, 3, level);
  return relief;
}

// The relief at uv, trilinear between mip levels. The normal is the blend of the texels' normals
// scaled to the blend of their lengths (layer 1's w, each texel's own): at level 0, whose normals are
// unit, it is normalised (interpolation between facets must not shorten it: at a sharp crease the blend
// of two unit normals is short, and relit would draw a dark line); above, each texel's normal is the
// mean of the unit normals under it, as short as they differ, and keeps that length.
CarbtfRelief carbtf_relief(vec2 uv, float lod) {
  CarbtfRelief relief;
  if (carbtf_hardware_filtering) {
    vec4 normal = textureLod(carbtf_range, vec3(uv, 1.0), lod);
    relief.normal = normal.xyz;
    relief.normal_length = normal.w;
    relief.tone = textureLod(carbtf_range, vec3(uv, 0.0), lod).yzw;
    relief.horizon_a = vec4(0.0);
    relief.horizon_b = vec4(0.0);
    if (carbtf_shadows_compiled) {
      relief.horizon_a = textureLod(carbtf_range, vec3(uv, 2.0), lod);
      relief.horizon_b = textureLod(carbtf_range, vec3(uv, 3.0), lod);
    }
  } else {
    CarbtfLod s = carbtf_split_lod(lod);
    relief = carbtf_relief_texel(carbtf_bilinear(uv, s.level), s.level);
    if (s.t > 0.0) {
      CarbtfRelief up = carbtf_relief_texel(carbtf_bilinear(uv, s.level + 1), s.level + 1);
      relief.normal = mix(relief.normal, up.normal, s.t);
      relief.normal_length = mix(relief.normal_length, up.normal_length, s.t);
      relief.tone = mix(relief.tone, up.tone, s.t);
      relief.horizon_a = mix(relief.horizon_a, up.horizon_a, s.t);
      relief.horizon_b = mix(relief.horizon_b, up.horizon_b, s.t);
    }
  }
  relief.normal *= relief.normal_length / length(relief.normal);
  return relief;
}

// The weights of the relief's 8 horizon azimuths (layers 2 and 3: 0-3 and 4-7) for a directional light
// (tangent frame): the two azimuths nearest the light's, linearly, and the light's elevation as a slope;
// computed once per light and shared by the reads of the relief at two levels (carbtf_material_shade()).
struct CarbtfHorizonWeights {
  vec4 a;
  vec4 b;
  float slope;    // light.z over its horizontal length
  bool overhead;  // a light from the zenith: nothing rises above it
};

CarbtfHorizonWeights carbtf_horizon_weights(vec3 light) {
  CarbtfHorizonWeights w;
  w.a = vec4(0.0);
  w.b = vec4(0.0);
  float across = length(light.xy);
  w.overhead = across <= 0.0;
  w.slope = w.overhead ? 0.0 : light.z / across;
  if (w.overhead) return w;
  float sector = atan(light.y, light.x) * (4.0 / CARBTF_PI);
  float base = floor(sector);
  int k0 = (int(base) % 8 + 8) % 8;
  int k1 = (k0 + 1) % 8;
  float t = sector - base;
  // Constant indices only: a dynamically indexed local array costs lavapipe a spill per read.
  for (int k = 0; k < 4; ++k) {
    w.a[k] = k == k0 ? 1.0 - t : (k == k1 ? t : 0.0);
    w.b[k] = k + 4 == k0 ? 1.0 - t : (k + 4 == k1 ? t : 0.0);
  }
  return w;
}

// The share of a directional light the relief leaves at a point: relief_visibility() of
// relief_horizons.hpp, the horizon interpolated between the two azimuths nearest the light's (there as
// h0 + t (h1 - h0), here as (1 - t) h0 + t h1: equal but for rounding; the C++ form stays, since the
// analysis' shadow fit reads it and its choices would move).
float carbtf_relief_visibility(CarbtfRelief relief, CarbtfHorizonWeights w) {
  if (w.overhead) return 1.0;
  float horizon = dot(relief.horizon_a, w.a) + dot(relief.horizon_b, w.b);
  return clamp(0.5 + (w.slope - horizon) / CARBTF_RELIEF_SHADOW_SOFTNESS, 0.0, 1.0);
}

// The ray from the eye through the plane point uv, in the ray's parameter t (texels along the view
// direction from the plane): how far it runs above the relief there, its height minus the relief's.
float carbtf_ray_clearance(vec2 uv, vec2 uv_per_t, float view_z, float t, float lod) {
  return t * view_z - carbtf_header.parallax_scale * carbtf_height(uv + t * uv_per_t, lod);
}

// Parallax occlusion: the texture point the ray from the eye through the plane point uv meets first
// (view: tangent frame, unit, towards the eye). A point of height h seen at theta from the normal lies
// h tan(theta) texels along the view from the plane point below it, and a ridge hides what lies behind it,
// as the measurement's camera sees it: offset mapping (height x view.xy at the plane point, Welsh 2004)
// left facets turned away from the view in sight (docs/design.md 4.6). The march steps down the ray from the
// relief's top to its bottom (MaterialTablesHeader::parallax_top and parallax_bottom) at most
// CARBTF_PARALLAX_STEP_TEXELS across or down per step, refines between the last point above and the first
// below, and takes the chord's crossing between them. parallax_steps 0: offset mapping, one height read.
vec2 carbtf_parallax_uv(vec2 uv, vec3 view, float lod) {
  if (carbtf_probed(CARBTF_COST_PROBE_PARALLAX)) return uv;
  vec2 size = vec2(float(carbtf_header.width), float(carbtf_header.height));
  vec2 uv_per_t = vec2(view.x, -view.y) / size;  // texture up is -v
  if (carbtf_header.parallax_steps == 0u) return uv + carbtf_header.parallax_scale * carbtf_height(uv, lod) * uv_per_t;
  float across = length(view.xy);
  float view_z = max(view.z, CARBTF_PARALLAX_MIN_VIEW_Z);
  float t_above = carbtf_header.parallax_top / view_z;
  float t_below = carbtf_header.parallax_bottom / view_z;
  float span = t_above - t_below;
  if (!(span > 0.0) || across == 0.0) return uv;  // a flat relief, or a view straight down
  uint steps = clamp(uint(ceil(span * max(across, view_z) / CARBTF_PARALLAX_STEP_TEXELS)), 1u,
                     carbtf_header.parallax_steps);
  float dt = span / float(steps);
  float top = t_above;
  float f_above = carbtf_ray_clearance(uv, uv_per_t, view_z, t_above, lod);
  float f_below = 0.0;
  for (uint i = 1u; i <= steps; ++i) {
    float t = top - float(i) * dt;
    float f = carbtf_ray_clearance(uv, uv_per_t, view_z, t, lod);
    if (f <= 0.0 || i == steps) {
      t_below = t;
      f_below = f;
      break;
    }
    t_above = t;
    f_above = f;
  }
  for (uint i = 0u; i < CARBTF_PARALLAX_REFINEMENTS; ++i) {
    float t = 0.5 * (t_above + t_below);
    float f = carbtf_ray_clearance(uv, uv_per_t, view_z, t, lod);
    if (f > 0.0) {
      t_above = t;
      f_above = f;
    } else {
      t_below = t;
      f_below = f;
    }
  }
  float t = f_above > f_below ? t_above - f_above * (t_above - t_below) / (f_above - f_below) : t_below;
  return uv + t * uv_per_t;
}
vec2 carbtf_parallax_uv(vec2 uv, vec3 view) {
  return carbtf_parallax_uv(uv, view, 0.0);
}

// The azimuthal equidistant projection of a unit direction into the unit disk (direction_interpolation.hpp).
// theta from |xy| and z (carbtf_polar_angle, accurate to 1e-7) rather than acos(z), which is
// ill-conditioned near the normal (a rounding of z by 6e-8 moves theta by 1e-4), or the device's atan,
// which Vulkan lets be 4096 ULP off.
vec2 carbtf_project_direction(vec3 d) {
  float r = length(d.xy);
  float theta = carbtf_polar_angle(r, d.z);
  vec2 azimuth = r > 0.0 ? d.xy / r : vec2(1.0, 0.0);
  return (theta / (0.5 * CARBTF_PI)) * azimuth;
}

// Barycentric weights of the measured directions around projected point p: the triangle of p's grid
// cell that holds p, or (outside every triangle) the nearest point of the cell's boundary edges;
// weights under CARBTF_LOOKUP_MIN_WEIGHT dropped.
void carbtf_direction_weights(DirectionLookupGpu set, vec2 p, out uvec3 index, out vec3 weight) {
  index = uvec3(0u);
  weight = vec3(1.0, 0.0, 0.0);
  int g = int(set.grid_size);
  ivec2 cell = clamp(ivec2(floor((p * 0.5 + 0.5) * float(g))), ivec2(0), ivec2(g - 1));
  uint c = uint(cell.y * g + cell.x);
  uvec4 cells = carbtf_table_quad(set.cells + (c >> 1));
  uvec2 range = (c & 1u) == 0u ? cells.xy : cells.zw;
  float best_inside = -1.0e30;
  float best_distance = 1.0e30;
  uvec3 edge_index = uvec3(0u);
  vec3 edge_weight = vec3(1.0, 0.0, 0.0);
  for (uint e = range.x; e < range.y; ++e) {
    uint base = set.entries + CARBTF_LOOKUP_ENTRY_QUADS * e;
    uvec4 head = carbtf_table_quad(base);
    vec4 points = uintBitsToFloat(carbtf_table_quad(base + 1u));
    vec2 a = points.xy, b = points.zw;
    if ((head.x & CARBTF_LOOKUP_EDGE_BIT) == 0u) {
      vec2 q = uintBitsToFloat(carbtf_table_quad(base + 2u).xy);
      vec2 ab = b - a, aq = q - a;
      float area = ab.x * aq.y - ab.y * aq.x;
      vec2 pb = b - p, pq = q - p;
      float la = (pb.x * pq.y - pb.y * pq.x) / area;
      vec2 ap = p - a;
      float lb = (ap.x * aq.y - ap.y * aq.x) / area;
      vec3 l = vec3(la, lb, 1.0 - la - lb);
      float inside = min(l.x, min(l.y, l.z));
      if (inside > best_inside) {
        best_inside = inside;
        index = head.xyz;
        l = max(l, vec3(0.0));
        weight = l / (l.x + l.y + l.z);
      }
    } else {
      uint i0 = head.x & ~CARBTF_LOOKUP_EDGE_BIT, i1 = head.y;
      vec2 ab = b - a;
      float s = clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
      vec2 d = a + s * ab - p;
      float distance = dot(d, d);
      if (distance < best_distance) {
        best_distance = distance;
        edge_index = uvec3(i0, i1, i1);
        edge_weight = vec3(1.0 - s, s, 0.0);
      }
    }
  }
  if (best_inside < -CARBTF_LOOKUP_INSIDE_SLACK && best_distance < 1.0e30) {
    index = edge_index;
    weight = edge_weight;
  }
  weight = mix(weight, vec3(0.0), lessThan(weight, vec3(CARBTF_LOOKUP_MIN_WEIGHT)));
  weight /= weight.x + weight.y + weight.z;
}

// Entries a and a + 1 in ascending direction index.
void carbtf_order_adjacent(inout uvec3 index, inout vec3 weight, int a) {
  if (index[a] > index[a + 1]) {
    uint i = index[a];
    index[a] = index[a + 1];
    index[a + 1] = i;
    float w = weight[a];
    weight[a] = weight[a + 1];
    weight[a + 1] = w;
  }
}

// Ascending direction index, by the compare-and-swap network couple_pair_weights() sorts with.
void carbtf_order_by_index(inout uvec3 index, inout vec3 weight) {
  carbtf_order_adjacent(index, weight, 0);
  carbtf_order_adjacent(index, weight, 1);
  carbtf_order_adjacent(index, weight, 0);
}

// Pair p's part of the interpolated colour before the relief tone: weight w times the pair's gain times
// its subspace image at uv, and the share of the relief tone the image takes (its tone weight); nothing
// where the pair has no layer.
vec3 carbtf_pair_colour(uint p, float w, vec2 uv, float lod, CarbtfLod s, CarbtfBilinear b, CarbtfBilinear b_up,
                        out float tone_weight) {
  tone_weight = 0.0;
  if (w == 0.0) return vec3(0.0);
  uvec4 quad = carbtf_probed(CARBTF_COST_PROBE_PAIR_READS) ? uvec4(p % 16u, 0x10040100u, p % 16u, 0x10040100u)
                                                         : carbtf_table_quad(carbtf_header.pair_table + (p >> 1));
  uvec2 entry = (p & 1u) == 0u ? quad.xy : quad.zw;
  uint layer = entry.x & 0xFFFFu;
  if (layer == CARBTF_PAIR_NO_LAYER) return vec3(0.0);
  tone_weight = unpackHalf2x16(entry.x).y;
  vec3 texel;
  if (carbtf_probed(CARBTF_COST_PROBE_SUBSPACE_READS)) {
    texel = vec3(float(layer) / 16.0);
  } else if (carbtf_hardware_filtering) {
    texel = textureLod(carbtf_subspaces, vec3(uv, float(layer)), lod).rgb;
  } else {
    texel = carbtf_subspace_texel(b, layer, s.level);
    if (s.t > 0.0) texel = mix(texel, carbtf_subspace_texel(b_up, layer, s.level + 1), s.t);
  }
  vec3 gain = vec3(uvec3(entry.y, entry.y >> 10, entry.y >> 20) & 1023u) * (1.0 / CARBTF_PAIR_GAIN_UNITS);
  return w * (gain * texel);
}

// The smooth BTF under two relief tones at once (the same texel reads): the tone at the fragment
// (`fine`) and the one its chroma takes (`chroma`, carbtf_material_shade()).
struct CarbtfBtf {
  vec3 fine;
  vec3 chroma;
};

// Adds a pair's part (carbtf_pair_colour()) to both sums: each with its share of its tone,
// max(1 + tone weight * (tone - 1), 0) per channel.
void carbtf_add_pair(inout CarbtfBtf btf, vec3 part, float tone_weight, vec3 fine_offset, vec3 chroma_offset) {
  btf.fine += max(1.0 + tone_weight * fine_offset, vec3(0.0)) * part;
  btf.chroma += max(1.0 + tone_weight * chroma_offset, vec3(0.0)) * part;
}

// The measured directions of `set` (the lights or the views) around a tangent-frame direction and
// their weights: the lookup, or the cost probe's constants.
void carbtf_measured_weights(DirectionLookupGpu set, vec3 direction, out uvec3 index, out vec3 weight) {
  if (carbtf_probed(CARBTF_COST_PROBE_LOOKUPS)) {
    index = uvec3(0u, 1u, 2u) % max(set.count, 1u);
    weight = vec3(0.5, 0.3, 0.2);
  } else {
    carbtf_direction_weights(set, carbtf_project_direction(direction), index, weight);
  }
}

// The smooth BTF colour at (already parallax-shifted) uv for a tangent-frame light direction and the
// view's measured directions vi and weights vw (carbtf_measured_weights(): a fragment lit by several lights
// looks the view up once), with the relief tones `tone` and `chroma_tone` at uv (one per colour channel):
// sum over the (light, view) pairs around the directions (the 3 x 3 nearest, or the staircase's 5 of them:
// carbtf_pair_coupling) of weight * max(1 + tone weight * (tone - 1), 0) * (pair gain * subspace image
// of the pair), per channel, as render_reference.cpp computes it.
CarbtfBtf carbtf_interpolated_btf(vec2 uv, vec3 light, uvec3 vi, vec3 vw, vec3 tone, vec3 chroma_tone, float lod) {
  uvec3 li;
  vec3 lw;
  carbtf_measured_weights(carbtf_header.lights, light, li, lw);
  CarbtfLod s = carbtf_split_lod(lod);
  CarbtfBilinear b = carbtf_bilinear(uv, s.level);
  CarbtfBilinear b_up = carbtf_bilinear(uv, s.level + (s.t > 0.0 ? 1 : 0));
  CarbtfBtf btf = CarbtfBtf(vec3(0.0), vec3(0.0));
  uint views = carbtf_header.views.count;
  vec3 fine_offset = tone - 1.0, chroma_offset = chroma_tone - 1.0;
  float tone_weight;
  if (carbtf_pair_coupling == CARBTF_PAIR_COUPLING_STAIRCASE) {
    carbtf_order_by_index(li, lw);
    carbtf_order_by_index(vi, vw);
    uint i = 0u, j = 0u;
    float light_left = lw[0], view_left = vw[0];
    for (uint k = 0u; k < CARBTF_STAIRCASE_STEPS; ++k) {
      // The two sides' sums agree only to rounding: what one overdraws is never negative weight.
      float w = max(min(light_left, view_left), 0.0);
      vec3 part = carbtf_pair_colour(li[i] * views + vi[j], w, uv, lod, s, b, b_up, tone_weight);
      carbtf_add_pair(btf, part, tone_weight, fine_offset, chroma_offset);
      if (carbtf_staircase_next_is_light(light_left, view_left, i, j)) {
        view_left -= light_left;
        i = min(i + 1u, 2u);
        light_left = lw[i];
      } else {
        light_left -= view_left;
        j = min(j + 1u, 2u);
        view_left = vw[j];
      }
    }
  } else {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        vec3 part = carbtf_pair_colour(li[i] * views + vi[j], lw[i] * vw[j], uv, lod, s, b, b_up, tone_weight);
        carbtf_add_pair(btf, part, tone_weight, fine_offset, chroma_offset);
      }
    }
  }
  return btf;
}

// What the material at one point and view is, whatever the light: the relief there and one mip level
// above (its chroma, carbtf_material_shade()) and the view's lookup. A fragment lit by several lights
// computes it once (carbtf_material_surface()) and shades each light from it, which saves the relief
// reads and a lookup per light after the first.
struct CarbtfSurface {
  vec2 uv;  // parallax-shifted
  vec3 view;
  float lod;
  CarbtfRelief relief;
  CarbtfRelief chroma_relief;
  uvec3 view_index;
  vec3 view_weight;
};

CarbtfSurface carbtf_material_surface(vec2 uv, vec3 view, float lod) {
  CarbtfSurface surface;
  surface.uv = uv;
  surface.view = view;
  surface.lod = lod;
  if (carbtf_probed(CARBTF_COST_PROBE_RELIEF)) {
    surface.relief = CarbtfRelief(vec3(0.0, 0.0, 1.0), 1.0, vec3(1.0), vec4(0.0), vec4(0.0));
    surface.chroma_relief = surface.relief;
  } else {
    surface.relief = carbtf_relief(uv, lod);
    surface.chroma_relief = carbtf_relief(uv, min(lod + float(carbtf_header.relief_chroma_levels), float(max(carbtf_header.relief_levels, 1u) - 1u)));
  }
  carbtf_measured_weights(carbtf_header.views, view, surface.view_index, surface.view_weight);
  return surface;
}

// The relief under a light (tangent frame, unit): the relit factor, max(N.L, 0) / max(L.z, light_z_floor)
// (the measured images already hold the flat surface's cosine falloff, L.z, so the relit factor swaps it
// for the local facet's and a flat range map changes nothing; beyond the last measured elevation the
// interpolation holds that ring's images, whose falloff is the floor's, so the floor keeps the product
// bounded at grazing light) where the relief casts no shadow, over an ambient share; and its specular
// lobe (RangeTiles::specular_strength), grey, where the facet turns to the half vector. Above level 0 the
// normal is the mean of the facets' (shorter where they differ): its length scales N.L as their mean
// would, but the lobe's power of a shortened N.H would dim it to nothing, so the lobe takes its direction.
struct CarbtfLit {
  float relit;
  float lobe;
};

// The lobe's gain at `view` (specular_view_gain(), material.hpp).
float carbtf_specular_view_gain(vec3 view) {
  if (carbtf_header.specular_view_power == 0.0) return 1.0;
  return pow(max(view.z, CARBTF_SPECULAR_VIEW_FLOOR), -carbtf_header.specular_view_power);
}

// `lobe_strength`: the lobe's at this view, carbtf_header.specular_strength times its view gain.
CarbtfLit carbtf_relief_lit(CarbtfRelief relief, vec3 light, vec3 half_vector, float lobe_strength,
                            CarbtfHorizonWeights horizon) {
  float n_dot_l = max(dot(relief.normal, light), 0.0);
  float visibility = 1.0;
  if (carbtf_shadows_compiled && carbtf_header.shadows != 0u) visibility = carbtf_relief_visibility(relief, horizon);
  CarbtfLit lit;
  lit.relit = CARBTF_RELIEF_AMBIENT +
              (1.0 - CARBTF_RELIEF_AMBIENT) * n_dot_l / max(light.z, carbtf_header.light_z_floor) * visibility;
  lit.lobe = 0.0;
  if (lobe_strength > 0.0) {
    float n_dot_h = max(dot(relief.normal, half_vector), 0.0) / relief.normal_length;
    lit.lobe = lobe_strength * n_dot_l * visibility * pow(n_dot_h, carbtf_header.specular_gloss);
  }
  return lit;
}

const vec3 CARBTF_LUMA_WEIGHTS = vec3(CARBTF_LUMA_RED, CARBTF_LUMA_GREEN, CARBTF_LUMA_BLUE);

// The material under one light: the interpolated smooth BTF, each image with its share of the relief
// tone, times the relit factor of the range map, plus the relief's specular lobe (carbtf_relief_lit()).
// Its brightness follows the relief at the fragment's level, its chroma the relief
// RangeTiles::chroma_levels mip levels above: in encoded values, the luma (Rec. 601) of the fragment's
// colour plus the colour differences of the same BTF under that coarser relief (its relit factor, lobe
// and, where the tone is one grey plane, tone). A JPEG's colour is band-limited (4:2:0 chroma), so the
// creases and facets of such a measurement at periods of 2 to 8 texels are brightness alone; with the
// relief's full-resolution chroma the model's a* and b* followed them (docs/design.md 4.6). A coloured tone (three
// planes) is the albedo's own colour and keeps the fragment's level. Directions are unit vectors in the
// tangent frame; zero below the horizon.
// `lod`: carbtf_material_lod() of the fragment (0, level 0 only, where the host has none). Under several
// lights, shade each from one carbtf_material_surface(uv, view, lod); the other forms build it per call.
vec3 carbtf_material_shade(CarbtfSurface surface, vec3 light) {
  vec3 view = surface.view;
  if (light.z <= 0.0 || view.z <= 0.0) return vec3(0.0);
  vec3 half_vector = normalize(light + view);
  CarbtfHorizonWeights horizon = carbtf_horizon_weights(light);
  float lobe_strength = carbtf_header.specular_strength * carbtf_specular_view_gain(view);
  CarbtfLit lit = carbtf_relief_lit(surface.relief, light, half_vector, lobe_strength, horizon);
  CarbtfLit chroma_lit = carbtf_relief_lit(surface.chroma_relief, light, half_vector, lobe_strength, horizon);
  vec3 chroma_tone = carbtf_header.tone_planes == 1u ? surface.chroma_relief.tone : surface.relief.tone;
  CarbtfBtf btf = carbtf_interpolated_btf(surface.uv, light, surface.view_index, surface.view_weight,
                                          surface.relief.tone, chroma_tone, surface.lod);
  vec3 colour = lit.relit * btf.fine + lit.lobe;
  vec3 chroma_colour = chroma_lit.relit * btf.chroma + chroma_lit.lobe;
  vec3 encoded = pow(max(colour, vec3(0.0)), vec3(CARBTF_CHROMA_GAMMA));
  vec3 chroma_encoded = pow(max(chroma_colour, vec3(0.0)), vec3(CARBTF_CHROMA_GAMMA));
  vec3 mixed = dot(encoded, CARBTF_LUMA_WEIGHTS) + (chroma_encoded - dot(chroma_encoded, CARBTF_LUMA_WEIGHTS));
  return pow(max(mixed, vec3(0.0)), vec3(1.0 / CARBTF_CHROMA_GAMMA));
}
vec3 carbtf_material_shade(vec2 uv, vec3 light, vec3 view, float lod) {
  return carbtf_material_shade(carbtf_material_surface(uv, view, lod), light);
}
vec3 carbtf_material_shade(vec2 uv, vec3 light, vec3 view) {
  return carbtf_material_shade(uv, light, view, 0.0);
}

#endif  // CARBTF_MATERIAL_GLSL
