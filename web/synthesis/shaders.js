// SPDX-License-Identifier: GPL-2.0-or-later
// GLSL ES 3.00 sources of the synthesis passes (Lefebvre & Hoppe 2005 "Parallel controllable texture synthesis",
// anisometric variant, with the appearance space and k-coherence of Lefebvre & Hoppe 2006).
//
// Conventions shared by all passes:
// * Synthesis state S (RGBA32F, per atlas texel of the current level; during a level split into four
//   parity-class quarters, see below): xy = exemplar coordinate in exemplar pixels, continuous (pixel i spans
//   [i, i+1)), wrapped to [0, m); w = 1 inside the atlas charts (and their gutter), 0 elsewhere.
// * Jacobian J (RGBA32F, per atlas texel of the level): the 2x2 map from atlas-texel offsets to exemplar-pixel
//   offsets, stored column-major (J e_x, J e_y) = (x, y, z, w); all zero outside the charts.
// * Exemplar tables (RGBA32F, m x m, read with texelFetch and `& (m - 1)` wrapping): appearance vectors (8 numbers
//   in two textures), reduced neighbourhood vectors (two textures), k-coherence candidates (two (x, y) pairs).

const HEADER = `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
`;

const HASH = `
// pcg3d (Jarzynski & Olano 2020): a stateless hash of (texel, level, seed).
uvec3 pcg3d(uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z; v.y += v.z * v.x; v.z += v.x * v.y;
  return v;
}
vec2 hash2(ivec2 p, int level, int seed) {
  uvec3 h = pcg3d(uvec3(uint(p.x), uint(p.y), uint(level * 7919 + seed)));
  return vec2(h.xy >> 8u) * (1.0 / 16777216.0);
}
`;

// ---------------------------------------------------------------------------------------------- Jacobian raster
// The atlas's map of faces, drawn once per atlas: the triangles (and the gutter's quads) in texture space, each
// texel getting where its face's data begin in the per-corner textures and its barycentric coordinates there
// (RGBA32F: column + 1, row, b1, b2; 0 where no face is). aCorner: the corner 3f + k whose field the vertex takes
// (a gutter quad's vertex takes one of its edge's). uWidth, a multiple of 3, keeps a face's corners in one row.
export const LOCATOR_VS = `#version 300 es
in vec2 aUV;
in int aCorner;
uniform int uWidth;
flat out vec2 vAt;
out vec2 vBary;
void main() {
  int k = aCorner % 3, first = aCorner - k;
  vAt = vec2(float(first % uWidth + 1), float(first / uWidth));
  vBary = vec2(k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0);
  gl_Position = vec4(aUV * 2.0 - 1.0, 0.0, 1.0);
}`;

export const LOCATOR_FS = `${HEADER}
flat in vec2 vAt;
in vec2 vBary;
out vec4 outL;
void main() { outL = vec4(vAt, vBary); }`;

// The Jacobian of every texel, a full-screen pass per field: the texel's face and barycentric coordinates from
// the map, that face's three corners' field (3D) interpolated there, and the face's G1 = dX/du, G2 = dX/dv
// (surface displacement per unit of u and v) and unit normal. Per-corner data lives in RGBA32F textures, corner
// c (= 3f + k) at texel c row by row: the field's corners, and the frames (G1, G2, normal at 3f, 3f + 1, 3f + 2);
// the map says where a face's three begin, so no texel here divides (SwiftShader shades every texel of the atlas).
// At each texel the field, projected into the face plane, gives the orthonormal frame (e1 along
// the field, e2 = n x e1) that the exemplar's (x, y) axes map to; an atlas displacement du then moves the exemplar
// coordinate by ([e1; e2] G du) / rho, so the texture has unit physical scale on the surface whatever the atlas's
// (even anisotropic) distortion is.
export const JACOBIAN_FS = `${HEADER}
uniform sampler2D uLocator;   // the atlas's map of faces
uniform sampler2D uField;     // per corner
uniform sampler2D uFrames;    // per face: G1, G2, normal
uniform float uInvRho;        // exemplar pixels per surface length unit
uniform float uTexel;         // UV units per atlas texel (1 / resolution)
uniform float uMagRef;        // reference field magnitude (magnitude scale 1)
uniform float uMagExponent;   // features scale with (|field| / ref)^exponent; 0 = direction only
out vec4 outJ;
vec3 corner(sampler2D t, ivec2 c, int k) { return texelFetch(t, c + ivec2(k, 0), 0).xyz; }
void main() {
  vec4 at = texelFetch(uLocator, ivec2(gl_FragCoord.xy), 0);
  if (at.x == 0.0) {
    outJ = vec4(0.0);
    return;
  }
  ivec2 c = ivec2(at.xy) - ivec2(1, 0);
  vec3 field = (1.0 - at.z - at.w) * corner(uField, c, 0) + at.z * corner(uField, c, 1);
  field += at.w * corner(uField, c, 2);
  vec3 G1 = corner(uFrames, c, 0), G2 = corner(uFrames, c, 1), n = corner(uFrames, c, 2);
  vec3 v = field - n * dot(field, n);
  float mag = length(v);
  // A vanishing field (singularities, no constraints yet) keeps the exemplar's x-axis along the chart's u-axis.
  vec3 e1 = mag > 1e-12 ? v / mag : normalize(G1 - n * dot(G1, n));
  vec3 e2 = cross(n, e1);
  float scale = 1.0;
  if (uMagExponent != 0.0) scale = clamp(pow(max(mag, 1e-12) / uMagRef, uMagExponent), 0.125, 8.0);
  float k = uInvRho * uTexel / scale;
  // Column-major: (J e_u, J e_v).
  outJ = k * vec4(dot(e1, G1), dot(e2, G1), dot(e1, G2), dot(e2, G2));
}`;

// One level coarser: texels twice as large, so J doubles; the mean over the valid children.
export const JACOBIAN_DOWN_FS = `${HEADER}
uniform sampler2D uJac;   // the finer level
out vec4 outJ;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 sum = vec4(0.0);
  float count = 0.0;
  for (int k = 0; k < 4; ++k) {
    vec4 j = texelFetch(uJac, 2 * p + ivec2(k & 1, k >> 1), 0);
    if (j != vec4(0.0)) { sum += j; count += 1.0; }
  }
  outJ = count > 0.0 ? 2.0 * sum / count : vec4(0.0);
}`;

// ---------------------------------------------------------------------------------------------- synthesis
// The state of a level lives in four quarter-size textures, one per parity class c = (x mod 2) + 2 (y mod 2):
// texel p is texel p >> 1 of quarter (p.x & 1) + 2 (p.y & 1). A correction sub-pass then shades exactly the texels
// it changes (one full quarter) instead of one texel in every 2x2 quad — GPUs, SwiftShader included, shade whole
// quads, so the interleaved layout would cost four times as much.
const QUARTERS = `
uniform sampler2D uS0;
uniform sampler2D uS1;
uniform sampler2D uS2;
uniform sampler2D uS3;
vec4 fetchS(ivec2 p) {
  ivec2 h = p >> 1;
  int c = (p.x & 1) + 2 * (p.y & 1);
  if (c == 0) return texelFetch(uS0, h, 0);
  if (c == 1) return texelFetch(uS1, h, 0);
  if (c == 2) return texelFetch(uS2, h, 0);
  return texelFetch(uS3, h, 0);
}
`;

// Coarsest level (no parent) or upsampling from the parent level, then jitter (LH05 Sec. 3.2, 3.3, 5), for the
// texels of one parity class (uClass = their offset in their 2x2 block):
//   S_l[p] = S_{l-1}[p / 2] + J_l(p) (p mod 2 - 1/2) + round(J_l(p) r_l (2 H(p) - 1)),
// H a hash in [0, 1)^2, r_l the level's randomness in level texels. The jitter is rounded to whole exemplar
// pixels so that every patch keeps the sub-pixel phase its coordinates got from the coarsest level: continuations
// of a neighbour's patch are then exactly continuous, not just to within a fraction of a pixel.
export const UPSAMPLE_FS = `${HEADER}${HASH}
uniform sampler2D uParent;  // the parent level's state, unpacked (one texel per parent texel)
uniform sampler2D uJac;
uniform int uCoarsest;
uniform ivec2 uClass;
uniform float uJitter;
uniform int uLevel;
uniform int uSeed;
uniform float uM;
uniform sampler2D uRedo;    // a local run's texels to synthesize again (local-update.js), read where uLocal = 1
uniform int uLocal;
uniform sampler2D uOld;     // this class's quarter as it was: what the other texels keep
out vec4 outS;
void main() {
  ivec2 p = 2 * ivec2(gl_FragCoord.xy) + uClass;
  if (uLocal == 1 && texelFetch(uRedo, p, 0).r < 0.5) { outS = texelFetch(uOld, ivec2(gl_FragCoord.xy), 0); return; }
  vec4 jv = texelFetch(uJac, p, 0);
  if (jv == vec4(0.0)) { outS = vec4(0.0); return; }
  mat2 J = mat2(jv.xy, jv.zw);
  vec4 parent = uCoarsest == 1 ? vec4(0.0) : texelFetch(uParent, p >> 1, 0);
  // No parent texel (coarsest level, or a chart that only appears at this resolution): the coherent tiling.
  vec2 s = parent.w == 0.0 ? J * (vec2(p) + 0.5) : parent.xy + J * (vec2(uClass) - 0.5);
  s += round(J * (uJitter * (2.0 * hash2(p, uLevel, uSeed) - 1.0)));
  outS = vec4(s - uM * floor(s / uM), 0.0, 1.0);
}`;

// One correction sub-pass (LH05 Sec. 3.4 with anisometric neighbourhoods, Sec. 5) over the texels of parity class
// uClass. For exemplar-space neighbour offset d_k = h * o_k the neighbourhood reads texel q = p + round(J^-1 d_k) and
// corrects its coordinate by the residual: c_k = S[q] + d_k - J (q - p). The 8 appearance vectors at c_k,
// projected with the exemplar's neighbourhood PCA (y = sum_k B_k^T a_k - offset), are compared with the
// precomputed reduced neighbourhood of every candidate: from each neighbour q its coherent continuation
// S[q] - J (q - p) and its two k-coherence candidates moved the same way, plus the texel's current coordinate.
// A q in the gutter next to a seam stands for the surface across the seam: its state is read from the texel
// the seam indirection names (seams.js), so both sides of a seam synthesize one continuous texture.
// The best (squared distance; uKappa penalises the non-coherent ones) wins.
export const CORRECT_FS = `${HEADER}${QUARTERS}
uniform sampler2D uJac;
uniform sampler2D uIndir;   // seam indirection: gutter texel -> the texel across the seam (xy), z = 1 if any
uniform int uSeams;
uniform sampler2D uApp0;
uniform sampler2D uApp1;
uniform sampler2D uNbr0;
uniform sampler2D uNbr1;
uniform sampler2D uCand;
uniform mat4 uProj[32];
uniform vec4 uProjOff[2];
uniform ivec2 uSize;
uniform ivec2 uClass;
uniform int uMask;
uniform float uM;
uniform float uH;
uniform float uKappa;
uniform sampler2D uRedo;    // as the upsampling's
uniform int uLocal;
out vec4 outS;

const ivec2 OFFSETS[8] = ivec2[8](ivec2(-1, -1), ivec2(0, -1), ivec2(1, -1), ivec2(-1, 0),
                                  ivec2(1, 0), ivec2(-1, 1), ivec2(0, 1), ivec2(1, 1));

float score(vec2 c, vec4 y0, vec4 y1) {
  ivec2 t = ivec2(floor(c)) & uMask;
  vec4 a = texelFetch(uNbr0, t, 0) - y0;
  vec4 b = texelFetch(uNbr1, t, 0) - y1;
  return dot(a, a) + dot(b, b);
}

void main() {
  ivec2 p = 2 * ivec2(gl_FragCoord.xy) + uClass;
  vec4 self = fetchS(p);
  if (self.w == 0.0 || (uLocal == 1 && texelFetch(uRedo, p, 0).r < 0.5)) { outS = self; return; }
  vec4 jv = texelFetch(uJac, p, 0);
  mat2 J = mat2(jv.xy, jv.zw);
  mat2 Ji = inverse(J);
  vec4 y0 = -uProjOff[0];
  vec4 y1 = -uProjOff[1];
  vec2 cands[24];
  for (int k = 0; k < 8; ++k) {
    vec2 d = uH * vec2(OFFSETS[k]);
    ivec2 q = clamp(p + ivec2(round(Ji * d)), ivec2(0), uSize - 1);
    vec4 ind = uSeams == 1 ? texelFetch(uIndir, q, 0) : vec4(0.0);
    vec4 sq = fetchS(ind.z > 0.5 ? ivec2(ind.xy) : q);
    if (sq.w == 0.0) { q = p; sq = self; }
    vec2 back = J * vec2(q - p);
    vec2 c = sq.xy + d - back;
    ivec2 t = ivec2(floor(c)) & uMask;
    vec4 a0 = texelFetch(uApp0, t, 0);
    vec4 a1 = texelFetch(uApp1, t, 0);
    y0 += uProj[4 * k] * a0 + uProj[4 * k + 1] * a1;
    y1 += uProj[4 * k + 2] * a0 + uProj[4 * k + 3] * a1;
    vec4 kc = texelFetch(uCand, ivec2(floor(sq.xy)) & uMask, 0);
    vec2 f = fract(sq.xy) - back;
    cands[3 * k] = sq.xy - back;
    cands[3 * k + 1] = kc.xy + f;
    cands[3 * k + 2] = kc.zw + f;
  }
  vec2 best = self.xy;
  float bestScore = score(self.xy, y0, y1);
  for (int i = 0; i < 24; ++i) {
    float s = score(cands[i], y0, y1);
    if (i % 3 != 0) s *= 1.0 + uKappa;
    if (s < bestScore) { bestScore = s; best = cands[i]; }
  }
  outS = vec4(best - uM * floor(best / uM), 0.0, 1.0);
}`;

// The four quarters back into one texture (one texel per atlas texel of the level).
export const UNPACK_FS = `${HEADER}${QUARTERS}
out vec4 outS;
void main() {
  outS = fetchS(ivec2(gl_FragCoord.xy));
}`;

// Magnification (LH06 Sec. 5): the colour at atlas position x (in texels) blends the four nearest texels'
// patches with bilinear weights; texel t's patch continues its coordinate with its Jacobian,
// c_t = S[t] + J(t) (x - t - 1/2). Where neighbouring texels are coherent all four predict the same c, and
// where they are not (patch seams) the blend fades over one texel instead of stepping at the texel's edge.
// Texels outside the charts and their gutters (w = 0) do not take part. The page's renderer (render.js)
// shades with the same function.
export const MAGNIFY_GLSL = `
vec3 magnifiedColour(sampler2D coordTex, sampler2D jacTex, sampler2D exemplarTex, vec2 x, float m,
                     vec2 dxdx, vec2 dxdy, out float found) {
  ivec2 size = textureSize(coordTex, 0);
  vec2 f = x - 0.5;
  ivec2 p0 = ivec2(floor(f));
  vec2 w = f - vec2(p0);
  vec4 acc = vec4(0.0);
  for (int k = 0; k < 4; ++k) {
    ivec2 o = ivec2(k & 1, k >> 1);
    ivec2 t = p0 + o;
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) continue;
    vec4 s = texelFetch(coordTex, t, 0);
    if (s.w == 0.0) continue;
    float wt = (o.x == 1 ? w.x : 1.0 - w.x) * (o.y == 1 ? w.y : 1.0 - w.y) + 1e-6;
    vec4 jv = texelFetch(jacTex, t, 0);
    mat2 J = mat2(jv.xy, jv.zw);
    vec2 c = s.xy + J * (x - vec2(t) - 0.5);
    acc += wt * vec4(textureGrad(exemplarTex, c / m, J * dxdx / m, J * dxdy / m).rgb, 1.0);
  }
  found = acc.w;
  return acc.w > 0.0 ? acc.rgb / acc.w : vec3(0.0);
}
`;

// The exemplar's colours at the synthesized coordinates, uMag output pixels per atlas texel, magnified as
// above. uNearest = 1 instead reads the exemplar pixel of texel p's own patch (exact colours, for measurements).
export const RESOLVE_FS = `${HEADER}
uniform sampler2D uCoord;
uniform sampler2D uJac;
uniform sampler2D uExemplar;   // RGBA8, repeat, linear
uniform float uMag;
uniform float uM;
uniform int uMask;
uniform int uNearest;
out vec4 outColour;
${MAGNIFY_GLSL}
void main() {
  vec2 x = gl_FragCoord.xy / uMag;
  if (uNearest == 1) {
    ivec2 p = ivec2(floor(x));
    vec4 s = texelFetch(uCoord, p, 0);
    if (s.w == 0.0) { outColour = vec4(0.0); return; }
    vec4 jv = texelFetch(uJac, p, 0);
    vec2 c = s.xy + mat2(jv.xy, jv.zw) * (x - vec2(p) - 0.5);
    outColour = vec4(texelFetch(uExemplar, ivec2(floor(c)) & uMask, 0).rgb, 1.0);
    return;
  }
  float found;
  vec3 colour = magnifiedColour(uCoord, uJac, uExemplar, x, uM, vec2(1.0 / uMag, 0.0), vec2(0.0, 1.0 / uMag), found);
  outColour = found > 0.0 ? vec4(colour, 1.0) : vec4(0.0);
}`;

// Seam resolve (LH06 Sec. 6.2, for rendering): a gutter texel next to a seam takes the exemplar coordinate of the
// surface point it stands for, read across the seam, so the magnification blend at a chart's edge continues the
// neighbouring chart's texture instead of this chart's own gutter synthesis. The indirection names that point to
// within a texel's fraction: the coordinate is the target texel's patch continued to it with the target's Jacobian
// (the texel centre alone would be up to 0.7 texel, i.e. J x 0.7 exemplar pixels, off). A texel that borrowed a
// neighbour's target continues that neighbour's resolved coordinate by its own Jacobian over the one-texel step.
export const SEAM_RESOLVE_FS = `${HEADER}
uniform sampler2D uCoord;
uniform sampler2D uJac;
uniform sampler2D uIndir;
uniform float uM;
out vec4 outS;
vec4 across(vec2 target) {
  ivec2 t = ivec2(floor(target));
  vec4 s = texelFetch(uCoord, t, 0);
  if (s.w == 0.0) return s;
  vec4 jv = texelFetch(uJac, t, 0);
  return vec4(s.xy + mat2(jv.xy, jv.zw) * (target - vec2(t) - 0.5), s.zw);
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 ind = texelFetch(uIndir, p, 0);
  vec4 own = texelFetch(uCoord, p, 0);
  if (ind.z > 0.5) {
    vec4 s = across(ind.xy);
    if (s.w != 0.0) {
      if (ind.w > 0.5) {
        // Borrowed from neighbour p + d: continue from there with this texel's Jacobian.
        int code = int(ind.w + 0.5) - 1;
        vec2 d = vec2(code % 3 - 1, code / 3 - 1);
        vec4 jv = texelFetch(uJac, p, 0);
        s.xy -= mat2(jv.xy, jv.zw) * d;
      }
      own = vec4(s.xy - uM * floor(s.xy / uM), s.zw);
    }
  }
  outS = own;
}`;

// A plain full-screen pass (one fetch per texel), the unit that synthesis times are reported in.
export const COPY_FS = `${HEADER}
uniform sampler2D uSource;
out vec4 outValue;
void main() {
  outValue = texelFetch(uSource, ivec2(gl_FragCoord.xy), 0) + vec4(1e-7);
}`;
