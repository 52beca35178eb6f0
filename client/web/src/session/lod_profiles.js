// The LOD profiles the page offers (docs/PROTOCOL.md 7.1 LodProfile): a few
// presets from coarse to fine. A document whose max_level is below a
// preset's refuses it; the page then steps the max level down (document_session.js).
// "balanced" is tessera-view's default profile (base 1, max 3, 15 degrees).
export const LOD_PRESETS = [
  { name: 'coarse', baseLevel: 0, maxLevel: 2, angle: 20, budget: 250000 },
  { name: 'balanced', baseLevel: 1, maxLevel: 3, angle: 15, budget: 1000000 },
  { name: 'fine', baseLevel: 1, maxLevel: 4, angle: 7.5, budget: 2000000 },
  { name: 'finest', baseLevel: 2, maxLevel: 5, angle: 4, budget: 4000000 },
];

export const DEFAULT_PRESET = 'balanced';

export function presetNamed(name) {
  return LOD_PRESETS.find((p) => p.name === name) ?? LOD_PRESETS.find((p) => p.name === DEFAULT_PRESET);
}

// The same profile one level shallower, or null at level 0.
export function shallower(profile) {
  if (profile.maxLevel === 0) return null;
  const maxLevel = profile.maxLevel - 1;
  return { ...profile, name: `${profile.name} (max ${maxLevel})`, maxLevel, baseLevel: Math.min(profile.baseLevel, maxLevel) };
}
