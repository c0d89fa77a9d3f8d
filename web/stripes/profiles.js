// SPDX-License-Identifier: GPL-2.0-or-later
// The stripe profiles as GLSL: how a fragment's phase becomes a colour, the same formulas as the core's bake
// (core/direction/stripe_texture.cpp stripeProfileValue), so that an exported GLB shows what the page showed.
// x, y: the two families' phases in periods (phase / 2π); w: the footprint of a pixel in periods (the
// filter's half-width); bricks and weave read a pattern at half the frequency (stripe_texture.h says why).
// And the phase inside a face (core/direction/stripe_pattern.h): the corners' phases
// interpolated, plus n·L(b) in a branch face, L the paper's piecewise-linear angle round the centroid.
// Imports nothing.

export const PROFILES = ['stripes', 'wood', 'grid', 'bricks', 'weave'];
export const TWO_FAMILY_PROFILES = ['grid', 'bricks', 'weave'];
export const PROFILE_LABELS = {
  stripes: 'Stripes',
  wood: 'Wood rings',
  grid: 'Grid lines',
  bricks: 'Bricks',
  weave: 'Weave',
};

export const profileIndex = (name) => PROFILES.indexOf(name);

// The width of a profile's lines as a share of a period, where none is asked for (core/direction/
// stripe_texture.h stripeDefaultWidth): stripes' dark bands, wood's late wood, grid lines, bricks' mortar, weave's
// threads.
export const DEFAULT_WIDTHS = { stripes: 0.5, wood: 0.7, grid: 0.12, bricks: 0.12, weave: 1 };

export const STRIPE_GLSL = /* glsl */ `
const float STRIPE_PI = 3.14159265358979;
float stripeFract(float x) { return x - floor(x); }
float offWhole(float x) { return abs(stripeFract(x + 0.5) - 0.5); }
float stripeLine(float x, float half_, float w) { return smoothstep(half_ - w, half_ + w, offWhole(x)); }

// stripe_pattern.cpp stripeAngle: 0, 2π/3, 4π/3 at the corners, linear along each edge.
float stripeAngle(vec3 b) {
  float l;
  if (b.z <= b.x && b.z <= b.y) l = (STRIPE_PI / 3.0) * (1.0 + (b.y - b.x) / (1.0 - 3.0 * b.z));
  else if (b.x <= b.y && b.x <= b.z) l = (STRIPE_PI / 3.0) * (3.0 + (b.z - b.y) / (1.0 - 3.0 * b.x));
  else l = (STRIPE_PI / 3.0) * (5.0 + (b.x - b.z) / (1.0 - 3.0 * b.y));
  return l >= 2.0 * STRIPE_PI ? l - 2.0 * STRIPE_PI : l;
}

// profile: the index in PROFILES; width: its lines' share of a period (DEFAULT_WIDTHS where none is asked for).
float stripeProfile(int profile, float x, float y, float w, float width) {
  float h = 0.5 * min(width, 1.0);
  if (profile == 0) {
    float soft = max(w, 0.4 * min(h, 0.5 - h));
    return smoothstep(h - soft, h + soft, offWhole(x));
  }
  if (profile == 1) {
    float late = 1.0 - smoothstep(0.0, h + w, offWhole(x));
    return 1.0 - 0.8 * late * late;
  }
  if (profile == 2) return min(stripeLine(x, h, w), stripeLine(y, h, w));
  float X = 2.0 * x, Y = 2.0 * y;
  if (profile == 3) {
    float row = floor(X + 0.5);
    float along = 0.5 * Y + 0.5 * (row - 2.0 * floor(0.5 * row));
    return min(stripeLine(X + 0.5, h, 2.0 * w), stripeLine(along, 0.5 * h, w));
  }
  float i = floor(X + 0.5), j = floor(Y + 0.5);
  bool alongOnTop = (i + j) - 2.0 * floor(0.5 * (i + j)) < 0.5;
  float d = alongOnTop ? X - i : Y - j;
  if (abs(d) > h) return 0.0;
  return 0.2 + 0.8 * sqrt(max(cos(STRIPE_PI * d * 0.5 / h), 0.0));
}
`;
